"""mech — analyse planar mechanisms described in YAML.

The package is usable without the command line::

    import mech
    m = mech.load("mechanisms/four_bar.yaml")
    count = mech.dof(m)              # Kutzbach and Grübler, worked
    print(count.formula)             # n = 3(4 − 1) − 2·4 − 0 = 1

Importing ``mech`` is cheap: numpy and rich are imported only by the analyses
and renderers that need them, so ``mech dof`` starts fast in a batch.
"""

from __future__ import annotations

# typing is not imported at run time: ``import mech`` is the console script's first step, before
# mech.entry can answer a Ctrl-C quietly, and typing (with re and enum) is most of its cost
TYPE_CHECKING = False
__version__ = "0.1.0"

__all__ = ["MechError", "__version__", "classify", "dof", "load", "loads"]

if TYPE_CHECKING:  # pragma: no cover
    from typing import Any

    from mech.errors import MechError
    from mech.loader import load, loads
    from mech.topology import classify, dof


def __getattr__(name: str) -> Any:
    """Resolve the public API lazily, so ``import mech`` stays cheap."""
    if name in ("load", "loads"):
        # The module is ``loader`` (not ``load``) so that ``mech.load`` stays the function.
        from mech import loader

        return getattr(loader, name)
    if name in ("dof", "classify"):
        from mech import topology

        return getattr(topology, name)
    if name == "MechError":
        from mech.errors import MechError

        return MechError
    raise AttributeError(f"module 'mech' has no attribute {name!r}")
