"""Registered fast forces: a hand-written kernel that a model's runs use instead of the
force generated from its energy, where the energy is the one the kernel implements.

A model's generated force (``numerics.models``) stays the reference; a fast force is
registered for the *content* of an energy (a hash the caller computes from the model's
fields, parameters and energy, never its name alone), so a user file that reuses a
built-in name with another energy still runs its own generated force. The fused flexMM
kernel of eq. `norm` (``_kernels.accel``) is the fast force of the paper chain written
as a model: ``flexmm_force`` (case II, fields theta and U) and ``flexmm_rotation_force``
(case I, theta alone); ``numerics.models`` registers them for the built-in models.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from numba import njit

from ._kernels import FASTMATH, _accel_passes

#: work rows of the fused kernel's force: sin, cos and 1 - cos of theta
FLEXMM_ROWS = 3


@njit(inline="always", fastmath=FASTMATH)
def _flexmm_force(u, p, out, S, coupled):
    """``accel``'s passes (``_kernels._accel_passes``, inlined) on the force's layout:
    u = (theta, U), p = (alpha^2, K_s, K_theta), S = (sin, cos, 1 - cos)."""
    # case I: U and aU stand in for arrays that the passes touch only when coupled
    # (no allocation per call: np.empty(0) twice cost 0.25 ns a site at N = 128)
    U = u[1] if coupled else u[0]
    aU = out[1] if coupled else out[0]
    _accel_passes(u[0], U, coupled, p[0], p[1], p[2], S[0], S[1], S[2], out[0], aU)


@njit(cache=True, nogil=True, fastmath=FASTMATH, boundscheck=False, error_model="numpy")
def flexmm_force(u, p, out, S):
    """The fused kernel's acceleration of eq. `norm`, case II, as a lattice force:
    u = (theta, U) (2, N), p = (alpha^2, K_s, K_theta), S (3, N) the trig rows."""
    _flexmm_force(u, p, out, S, True)


@njit(cache=True, nogil=True, fastmath=FASTMATH, boundscheck=False, error_model="numpy")
def flexmm_rotation_force(u, p, out, S):
    """The same for case I: u = (theta,) (1, N), no sliding."""
    _flexmm_force(u, p, out, S, False)


@dataclass(frozen=True)
class FastForce:
    """A registered fast force.

    Attributes
    ----------
    name : str
        What it is registered for (a model's name), for messages and listings.
    energy_hash : str or callable
        The content hash of the energy it implements, or a function returning it (called
        on the first lookup: a built-in model's hash is read from its file only then).
    force : Numba function
        ``force(u, p, out, S)`` (``numerics.lattice.ForceStepper``).
    rows : int
        Its work rows.
    parameters : callable
        The model's parameter values (a mapping name -> value) -> the force's ``p``.
    """

    name: str
    energy_hash: object
    force: object
    rows: int
    parameters: Callable

    def hash(self) -> str:
        if callable(self.energy_hash):
            return self.energy_hash()
        return self.energy_hash


_FAST_FORCES: dict[str, FastForce] = {}
_HASHES: dict[str, str] = {}  # name -> resolved energy hash


def register_fast_force(name: str, energy_hash, force, rows: int, parameters: Callable
                        ) -> FastForce:
    """Register ``force`` as the fast force of the energy of content hash ``energy_hash``
    (a string, or a function giving it on first lookup). See :class:`FastForce`."""
    if name in _FAST_FORCES:
        raise ValueError(f"a fast force for {name!r} registered twice")
    entry = FastForce(name, energy_hash, force, int(rows), parameters)
    _FAST_FORCES[name] = entry
    return entry


def fast_force(energy_hash: str) -> FastForce | None:
    """The fast force registered for an energy of this content hash, or None."""
    for name, entry in _FAST_FORCES.items():
        if name not in _HASHES:
            _HASHES[name] = entry.hash()
        if _HASHES[name] == energy_hash:
            return entry
    return None


def fast_forces() -> dict:
    """{name: FastForce} of every registered fast force."""
    return dict(_FAST_FORCES)
