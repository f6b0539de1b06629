"""The paper's statements per scene, for the docs builders (kept in the package, where
``saltdem-post compare`` reads them)."""
from saltdem_post.paper_statements import STATEMENTS, scene_key  # noqa: F401
