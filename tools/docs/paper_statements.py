"""The paper's statements per scene, for the docs builders (kept in the package, where
``saltdem-post compare`` reads them)."""
import os
import sys

_PY = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "python")
if _PY not in sys.path:
    sys.path.insert(0, _PY)

from saltdem_post.paper_statements import STATEMENTS, scene_key  # noqa: E402,F401
