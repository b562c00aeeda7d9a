"""numpy, imported the first time one of its names is used.

``bras-kit validate PKG_DIR`` on the tutorial's package needs no numpy: its URDF has no turned
shape and no inertia, and the node's formulas are followed with Python floats
(:meth:`bras_kit.model.expr.Expression.at`). numpy's import is a quarter of that command's time
(45-60 ms of about 0.2 s, issue 43), so the modules that command loads (the validator's solids
and inertia, kinematics, the formula evaluator, the motion package) name numpy through this
object rather than importing it::

    from typing import TYPE_CHECKING

    if TYPE_CHECKING:
        import numpy as np
    else:
        from .lazy_numpy import np

The first name looked up imports numpy and copies its namespace onto the object, so later
lookups cost what a module's attribute does (no call per lookup on the hot paths of the
10,000-link files). Nothing at a module's top level may use ``np``: that would import numpy again.

Why not :class:`importlib.util.LazyLoader` (or the ``lazy_loader`` package, built on it): it
puts a half-made ``numpy`` in ``sys.modules`` for every importer in the process, third-party
ones included; this object is seen by bras-kit's own modules only.
"""

from __future__ import annotations

from typing import Any


class _Numpy:
    """Stands for the numpy module until its first use (see the module's docstring)."""

    def __getattr__(self, name: str) -> Any:
        import numpy

        self.__dict__.update(vars(numpy))
        return getattr(numpy, name)  # names numpy makes on demand (np.random...) are not in its namespace

    def __repr__(self) -> str:
        return "<numpy, imported at its first use>"


np: Any = _Numpy()
