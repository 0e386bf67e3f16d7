"""The compile decorators under the kernels' former import path, :mod:`pool_env.sim.jit`.

Kept only while the spin kernels (``spin_*.py``, being edited on another branch) still
import them from here; once they import :mod:`pool_env.sim.jit`, this module goes
(issue 21 item 4).
"""

from pool_env.sim.jit import inline_kernel, kernel, parallel_kernel

__all__ = ["inline_kernel", "kernel", "parallel_kernel"]
