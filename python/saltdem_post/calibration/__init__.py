"""Calibration of SaltDEM materials against their emergent properties
(docs/validation.md): ``cli`` runs the decks of ``examples/calibration/``
(command line ``saltdem-calibrate``, or ``python3 -m
saltdem_post.calibration``), ``fit`` measures their results (biaxial peaks,
Mohr-Coulomb fit, angle of repose, Couette viscosity) and ``report`` writes
``report.md`` and the plots."""
