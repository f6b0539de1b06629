"""Calibration of SaltDEM materials against their emergent properties
(docs/validation.md): ``cli`` is the command line (``saltdem-calibrate``, or
``python3 -m saltdem_post.calibration``), ``experiments`` defines the runs of
the decks of ``examples/calibration/`` that ``runner`` executes, ``fit``
measures their results (biaxial peaks, Mohr-Coulomb fit, angle of repose,
Couette viscosity), ``writers`` keeps ``results.json`` and writes the
parameter files, and ``report`` writes ``report.md`` and the plots."""
