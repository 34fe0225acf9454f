"""Every slow growing offset of a spectrum checked at the next truncation, not only its
fastest (``_exact._Sidebands.checked``): ../shared/CONVENTIONS.md's rule, a mode counts
where it persists, at the same q, across truncations.

Probe 98 (bench/probe_exact98.py): on an FPUT ring (alpha 0.361, beta 1.761, k 2 pi 129/512,
a 0.384) the offset q = k, where the l = -1 copy is the lattice's uniform translation,
grew at 2.95e-6 (1.7e-6 omega) at P = 10 and at 0 at P = 14, 20 and 24 (the dense
eigenproblem alike): a truncation artefact a converged Hill code does not report, while
the fastest offset, the only one checked, persisted. Such artefacts are the size of the
truncated harmonics' weight; a real rate that small needs ~10^4 periods to grow e-fold.
Only the offsets below ``ARTEFACT_RATE`` omega are checked (a band's edges and weak
bands: a few offsets a spectrum), so the cost stays that of a few offsets at P + 4.
"""

from __future__ import annotations

import dataclasses

import numpy as np

#: growing offsets slower than this share of omega (other than the fastest, checked
#: already) are checked at P + PERSIST_STEP and dropped where they do not grow there:
#: 6x the artefact measured (1.7e-6 omega)
ARTEFACT_RATE = 1e-5


def slow_offsets_persist(spec, again):
    """``spec`` (a HillSpectrum at truncation P) with each slow growing offset that does
    not grow at the next truncation set to no growth; ``again(offsets)``: the spectrum at
    P + PERSIST_STEP at those offsets."""
    gain = spec.gain
    i_peak = int(np.argmax(gain))
    slow = np.flatnonzero((gain > 0) & (gain < ARTEFACT_RATE * spec.wave.omega))
    slow = slow[slow != i_peak]
    if not slow.size:
        return spec
    gone = slow[~(np.asarray(again(spec.offsets[slow]).gain) > 0)]
    if not gone.size:
        return spec
    gain, harmonic = gain.copy(), np.array(spec.harmonic, copy=True)
    offset = np.array(spec.sideband_offset, dtype=float, copy=True)
    gain[gone], harmonic[gone], offset[gone] = 0.0, 0, np.nan
    return dataclasses.replace(spec, gain=gain, harmonic=harmonic, sideband_offset=offset)
