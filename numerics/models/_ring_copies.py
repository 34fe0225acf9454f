"""The Hill spectrum of a one-field wave on a ring from each mode's copy that holds its
largest coordinate at l = 0 (issue 41: fput's ring theory at a tenth of its run).

On a ring of N sites with k = 2 pi m / N, the offsets q + s k (s integer) are ring offsets
too, and the Hill pencil is shift invariant: K_{l+s, h+s}(q) = K_lh(q + s k) and
(lambda - i (l + s) omega) = (lambda - i s omega) - i l omega, so a mode at offset q' with
harmonics h' is the mode at q = q' - s k with harmonics h = h' + s, its eigenvalue moved by
i s omega (the same rate). Only the truncation window l = -P..P does not move with it; a
mode the theory keeps holds < 1e-6 of its weight in the outer three harmonics, and the
copies' rates agree to 2e-10 relative (measured: fput, klein-gordon, sine-gordon rings,
every kept mode centred at l = +-1 against its copy centred at 0, dense eigenvalues).
At q' < 0 the copy is the complex conjugate of the mode at -q' with h' -> -h'.

Which copies. The kernel (``_sidebands``) keeps a mode centred at l = -1, 0, 1 (a tie of
harmonics at their mean) and finds it in the Gershgorin cluster that holds its largest
coordinate (one field: a coordinate is a harmonic). That coordinate is at a harmonic
h* with |h*| <= 2 (a tie {0, 2} centred at 1, the heaviest either). At q + h* k it is at
l = 0: the clusters that hold an l = 0 root (``sideband_modes(..., zero_only=True)``, about
half the clusters of fput's ring) at the offsets q + s k, s = -2..2, hold every mode kept at
q (q' = 0, not a ring offset, among them). Their weights are moved to q's harmonics (the
window's far end padded with zeros, its near end dropped: < 1e-6 of a kept mode's weight)
and the kept-mode rule applied at q as before (``_exact._Sidebands._keep``): the same
modes, rates within round-off of the per-offset solve. An offset whose sources include one
the kernel gave up on (count -1) is solved as before (``_Sidebands.spectrum``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: the shifts s of the sources q + s k: a kept mode's largest coordinate is at |h*| <= 2
SHIFTS = (-2, -1, 0, 1, 2)


def ring_copies(engine, N: int, m: int):
    """``engine.spectrum(ring_offsets(N))`` (``_exact._Sidebands``, one field) from the
    modes found at l = 0 (module docstring)."""
    from ._exact import MAX_CLUSTER, MAX_MODES, HillSpectrum, ring_offsets
    from ._sidebands import sideband_modes

    wave, P = engine.wave, engine.P
    offsets = ring_offsets(N)
    Q = offsets.size
    # the sources: the ring's offsets and q = 0 (the copies at l = +-1, +-2 of the modes
    # at q = k, 2k)
    lam, vec, count = sideband_modes(engine.Hh, engine.masses, wave.k, wave.omega, P,
                                     np.concatenate([[0.0], offsets]), engine.floor,
                                     MAX_MODES, MAX_CLUSTER, False, True)
    lam_t, vec_t, count_t = _copies(lam, vec, count, N, m, np.array(SHIFTS))
    gains = np.zeros(Q)
    modes = np.zeros(Q, int)
    offs = np.full(Q, math.nan)
    engine._keep(offsets, lam_t, vec_t, count_t, gains, modes, offs)
    redo = np.flatnonzero(count_t < 0)
    if redo.size:  # as before, offset by offset
        sub = engine.spectrum(offsets[redo])
        gains[redo], modes[redo], offs[redo] = sub.gain, sub.harmonic, sub.sideband_offset
    return HillSpectrum(wave=wave, offsets=offsets, gain=gains, harmonic=modes,
                        sideband_offset=offs, truncations=(P,))


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _copies(lam, vec, count, N, m, shifts):
    """Each ring offset's candidates (``_keep``'s lam, vec, count: its modes in its first
    slots, -1 where a source was given up) from the sources' modes (``lam``, ``vec``,
    ``count`` at the offsets 2 pi j' / N, j' = 0..N/2). Target j, shift s: the source
    j' = j + s m (mod N), mirrored to N - j' above N/2 (harmonic h' -> -h'); the copy's
    harmonic h' is the target's h' + s, zeros where it falls outside the window. Compiled:
    the same gathering in NumPy cost ~0.5 ms of fput's ~4.5 ms ring."""
    Q = N // 2
    n = vec.shape[2]
    total = np.zeros(Q, np.int64)
    bad = np.zeros(Q, np.bool_)
    for t in range(Q):
        for s in shifts:
            src = (t + 1 + s * m) % N
            if src > N // 2:
                src = N - src
            if count[src] < 0:
                bad[t] = True
            else:
                total[t] += count[src]
    width = max(1, total.max())
    lam_t = np.zeros((Q, width), np.complex128)
    vec_t = np.zeros((Q, width, n), np.complex128)
    for t in range(Q):
        r = 0
        for s in shifts:
            src = (t + 1 + s * m) % N
            mirror = src > N // 2
            if mirror:
                src = N - src
            for slot in range(max(count[src], 0)):
                lam_t[t, r] = lam[src, slot]  # only Re lambda (the rate) is read
                for i in range(n):
                    at = i - s
                    if mirror:
                        at = n - 1 - at
                    if 0 <= at < n:
                        vec_t[t, r, i] = vec[src, slot, at]
                r += 1
        if bad[t]:
            total[t] = -1
    return lam_t, vec_t, total
