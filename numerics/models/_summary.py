"""What ``flexmm coefficients --model`` reports: the NLS of a model at one carrier."""

from __future__ import annotations

import math
import re

import numpy as np

from energy import Model, ModelError

from ._linear import carrier_damping, check_amplitude, field_rule
from ._nls import nls
from ._wave import HARMONIC_CHECK

#: The NLS's own frequency shift beyond this share of omega is outside the weakly nonlinear
#: expansion (the paper chain's coefficients command warns at the same 10%).
WEAK_SHIFT = 0.10
#: An NLS band wider than this (rad/site) leaves the sidebands' half of the zone: offsets past
#: pi/2 are the lattice's backward pairs (``numerics.models.pair_kind``)
WIDE_BAND = math.pi / 2
#: The amplitude's field moving less than this share of the wave's largest field is said:
#: a = 0.1 of u on diatomic FPUT's acoustic branch at k = 3.14 is v = 125
SMALL_FIELD = 0.1


#: An amplitude past a quarter turn of a field the energy reads as an angle is said, with
#: its value in degrees and in rad had it been meant in degrees (newuser 102: flexmm-lossy
#: at a = 3, an experimentalist's "3 degrees", printed the exact lattice's amplification
#: 4.6e266, "observable", and no word on the unit; the paper chain's flags stop at 1.5 rad)
QUARTER_TURN = math.pi / 2


def angle_note(model: Model, field: str, a: float) -> str:
    """A sentence where ``a`` (rad) of ``field`` is past ``QUARTER_TURN`` and the model's
    energy holds cos, sin or tan of that field (of cell n or n + 1: an angle), else ''."""
    lat = model.lattice
    text = " ".join(str(e) for e in (lat.kinetic, lat.bond, lat.site) if e)
    if not a > QUARTER_TURN or not re.search(rf"\b(?:cos|sin|tan)\(\s*{re.escape(field)}"
                                             r"(?:_next)?\s*\)", text):
        return ""
    return (f"a = {a:g} of {field}, which the energy reads through cos/sin (an angle, in "
            f"rad), is {math.degrees(a):.4g} degrees, past a quarter turn; if a was meant in "
            f"degrees, give --amplitude {math.radians(a):.4g}")


def _num(x):
    """A plain float (not numpy's: the dict is JSON-ready), None where not finite."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def _unstable_rest(model: Model) -> str:
    """Why the model's rest state is no minimum (``check_rest_stable``'s message, and what
    it means for a wave), or ''."""
    from ._linear import check_rest_stable

    try:
        check_rest_stable(model)
    except ModelError as err:
        return (f"{err}: small waves there grow from rest (omega imaginary), so every "
                "state of the lattice, this wave included, is linearly unstable; g1, g2 and "
                "g describe its sidebands alone")
    return ""


def harmonic_resonance_note(model: Model, c, a: float, what: str) -> str:
    """A sentence where the carrier ``c``'s second harmonic at amplitude ``a`` is past
    ``HARMONIC_CHECK`` of its first (``second_harmonic_size``: near a second-harmonic
    resonance, 2 omega close to a branch at 2k), naming the branch and the amplitude below
    which it is not; '' elsewhere. ``what``: the theory that assumes the harmonic small.

    The NLS's g2 holds the harmonic's response 1/D(2k, 2 omega): across the resonance it
    changes sign through a pole, and so does its verdict (diatomic FPUT, m 2, alpha 0.5,
    a 0.05: g2 +20.7 'stable' at k 1.917, -21.5 'MI' at 1.937, the harmonic 1.9x the
    carrier at both, and no word said). The travelling wave distrusts its harmonic balance
    from the linear wave at the same size (``_wave.HARMONIC_CHECK``).
    """
    from ._fourwave_kernel import second_harmonic_size
    from ._linear import branches

    size = second_harmonic_size(model, c.k, a, car=c)
    if not size > HARMONIC_CHECK:  # nan: no harmonic to speak of
        return ""
    om2 = np.asarray(branches(model, 2 * c.k), float).ravel()
    b = int(np.argmin(np.where(np.isfinite(om2), np.abs(om2 - 2 * c.omega), np.inf)))
    near = (f"near branch {b}'s omega(2k) = {om2[b]:.4g}" if np.isfinite(om2[b])
            else "near a branch at 2k")
    size_text = f"{size:.2g} x" if math.isfinite(size) else "unbounded against"
    below = (f"; below a = {a * HARMONIC_CHECK / size:.2g} it is {HARMONIC_CHECK:g} of it"
             if math.isfinite(size) else "")
    return (f"the wave's second harmonic is {size_text} its carrier at a = {a:g} (2 omega = "
            f"{2 * c.omega:.4g} {near}: a second-harmonic resonance): {what} assumes it "
            f"small and slaved to the carrier{below}; the exact lattice theory holds")


def model_coefficients(model: Model, k: float, amplitude: float, branch=None) -> dict:
    """The semi-discrete NLS of ``model`` at carrier ``k`` and amplitude ``a``.

    Returns a JSON-ready dict: ``model``, ``parameters``, ``k``, ``amplitude``, ``branch``
    (index), ``field`` (the amplitude's field), ``field_rule`` (why that field), ``omega``, ``group_velocity``, ``g1``,
    ``g2``, ``g2_parts``, ``g``, ``verdict`` ("MI", "stable", "undefined"), ``reason``,
    ``peak_gain`` (1/time), ``e_folding_time``, ``fastest_offset``, ``band_edge`` (rad/site),
    ``second_harmonic`` / ``mean`` / ``mean_strain`` (amplitude per field at this a),
    ``frequency_shift`` and ``warnings``; a model with [dissipation] adds
    ``carrier_damping`` (the carrier branch's amplitude decay rate Gamma, 1/time). Non-finite numbers are None.
    """
    a = check_amplitude(amplitude)  # the carrier field's first harmonic
    r = nls(model, k, branch)
    c = r.carrier
    peak = r.peak_gain(a)
    warn = []
    # the NLS's own nonlinear scale |g2| a^2/4 (mean flow included: a modulation feels it)
    scale = abs(r.g2) * a * a / 4
    if not r.undefined and scale > WEAK_SHIFT * c.omega:
        share = scale / c.omega
        share = f"{share:.0%} of" if share < 10 else f"{share:.3g} times"  # not 30 digits
        warn.append(f"the NLS's frequency shift |g2| a^2/4 = {scale:.3g} "
                    f"is {share} omega: beyond the weakly "
                    "nonlinear expansion; lower the amplitude or ask the exact theory")
    if not r.undefined and (note := harmonic_resonance_note(model, c, a, "the NLS")):
        warn.append(note)
    edge = r.band_edge(a) if not r.undefined else math.nan
    if r.verdict == "MI" and math.isfinite(edge) and edge > WIDE_BAND:
        # a nearly flat branch (tiny g1): flat-kg, C 1e-3, k 2.5, a 0.1 put its NLS band
        # edge at 4.33 rad/site and its peak (0.00374 /time) at offset 3.06, where the
        # lattice's pair is a backward one (exact and four-wave 0.0030, a run 0.0027)
        warn.append(f"the NLS's band reaches offset {edge:.3g} rad/site (its fastest "
                    f"{r.fastest_offset(a):.3g}), beyond pi/2: the envelope's long-wave "
                    "expansion does not hold that far from the carrier (offsets past pi/2 "
                    "are the lattice's backward pairs); lower the amplitude, or trust the "
                    "four-wave and exact lattice theories (flexmm point's rows)")
    if model.lossy:  # a carrier that decays before its phase turns is no wave to modulate
        from ._linear import damped_frequencies

        w = complex(np.asarray(damped_frequencies(model, c.k))[c.branch])
        if abs(w.real) <= abs(w.imag):
            warn.append(f"the carrier is {'over' if abs(w.real) < 1e-9 * abs(w.imag) else ''}"
                        f"damped at k = {c.k:.4g}: its damped frequency is {w.real + 0.0:.3g} "
                        f"{w.imag:+.3g}i (it decays faster than its phase turns); the rates "
                        "above are the lossless wave's, lower the damping for a wave")
    from ._reach import amplitude_reach, energy_not_real

    reach = amplitude_reach(model, c.k, a, branch, carrier=c)
    verdict, reason, no_wave = r.verdict, r.undefined, False
    if reach < a:  # the NLS's numbers at this a would describe a wave that cannot exist
        warn.append(f"at amplitude {a:g} the model's energy is not real along the wave (at "
                    f"most a = {reach:.3g} at k = {c.k:.4g}): the NLS's gain, band and shift "
                    "here are of a wave the model cannot carry")
        # no verdict of a wave that does not exist (a map's cell says the same, ``_map``;
        # Toda at a = 2000 read 'stable'); g1, g2 and g stay: they do not depend on a
        if verdict != "undefined":
            verdict = "undefined"
            reason = energy_not_real(model, k, a, branch, carrier=c)
            peak, no_wave = math.nan, True
    unstable_rest = _unstable_rest(model)
    if unstable_rest and verdict == "undefined":
        warn.append(unstable_rest)
    elif unstable_rest:  # the lattice grows from rest: no wave of it is stable, whatever g
        verdict, reason = "undefined", unstable_rest
        peak, no_wave = math.nan, True
    fields = model.fields
    if note := angle_note(model, fields[c.field], a):
        warn.insert(0, note)  # first: it changes every other number
    e = np.abs(np.asarray(c.e))
    big = int(np.argmax(e))
    if e[c.field] < SMALL_FIELD * e[big]:  # a of a field that hardly moves: a huge wave
        warn.append(f"on branch {c.branch} at k = {c.k:.4g} the field {fields[c.field]} moves "
                    f"{e[c.field] / e[big]:.2g} of {fields[big]}: a = {a:g} of "
                    f"{fields[c.field]} is {fields[big]} = {a * e[big] / e[c.field]:.3g}; "
                    f"--branch {fields[big]} measures a in {fields[big]}")
    return {
        "model": model.name, "parameters": dict(model.params), "k": float(k),
        "amplitude": a, "branch": c.branch, "field": fields[c.field],
        "field_rule": field_rule(model, branch, c.field),
        "omega": c.omega, "group_velocity": c.group_velocity, "g1": c.g1,
        "g2": _num(r.g2), "g2_parts": {p: _num(v) for p, v in r.parts.items()},
        "g": _num(r.g), "verdict": verdict, "reason": reason,
        "peak_gain": _num(peak), "e_folding_time": _num(1 / peak) if peak and peak > 0
        else None,
        "fastest_offset": None if no_wave else _num(r.fastest_offset(a)),
        "band_edge": None if no_wave else _num(r.band_edge(a)),
        "second_harmonic": {f: _num(abs(v) * a**2 / 2) for f, v in
                            zip(fields, r.second_harmonic)},
        "mean": {f: _num(float(v) * a**2 / 4) for f, v in zip(fields, r.mean)},
        "mean_strain": {f: _num(float(v) * a**2 / 4) for f, v in zip(fields, r.strain)},
        "frequency_shift": _num(r.frequency_shift(a)) if not r.undefined else None,
        "warnings": warn,
    } | ({"carrier_damping": carrier_damping(model, c.k, c.branch)} if model.lossy else {})
