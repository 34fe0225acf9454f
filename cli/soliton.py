"""`flexmm soliton`: the envelope soliton a material carries at one k (bright or dark, width,
velocity, frequency, kink of U), and with --simulate the same measured in the lattice."""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

from common.files import write_results
from common.output import prepare_output, strict_json
from numerics.lattice import checks
from numerics.theory import (
    NLS_THEORIES,
    RunTooLong,
    SolitonWarning,
    simulate_soliton,
    soliton,
    soliton_report,
)

ROWS = (("velocity", "sites/T"), ("width", "sites"), ("amplitude", "rad (peak rotation)"),
        ("frequency", "1/T"), ("kink_height", "U, lattice units"))


#: the table's rows in SI (--physical): sites -> m, T -> s
SI_UNITS = {"velocity": "m/s", "width": "m", "frequency": "1/s"}


def _si(sol, run, units) -> dict:
    """{"predicted": {velocity, width, frequency}, "measured": ...} in m/s, m and 1/s."""
    a, T = units.metres_per_site, units.seconds_per_T
    scale = {"velocity": a / T, "width": a, "frequency": 1 / T}
    out = {"predicted": {key: sol.summary()[key] * f for key, f in scale.items()}}
    if run is not None:
        out["measured"] = {key: run.measured()[key] * f for key, f in scale.items()}
    return out


def _other_theory(mat, case, k, amplitude, theory):
    """The other NLS's kind at this point, or a sentence saying where it disagrees."""
    other = [t.label for t in NLS_THEORIES if t.label != theory][0]
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SolitonWarning)
            s = soliton(mat, case, k, amplitude, theory=other)
    except ValueError as exc:
        return other, None, str(exc)
    return other, s, None


def run_soliton(args, log=print) -> dict:
    from .point import material_from

    mat, units = material_from(args)
    if args.out:  # before any computation (a simulation may take minutes)
        prepare_output(args.out, cache=False)
    from ._resolved import check_paper_amplitude, check_peak_rotation

    amplitude = check_peak_rotation(args.amplitude, 1.0)
    k = checks.real("--k", args.k, 0.0, math.pi)

    check_paper_amplitude(mat, k, amplitude)
    theory = next(t.label for t in NLS_THEORIES if t.cli == args.theory)
    if args.simulate:
        from numerics.models import MIN_TRAVEL  # probe 99: 1e-100 said "dt > t_end"

        checks.real("--travel", args.travel, MIN_TRAVEL, 1000.0, low_open=False)
        if args.N is not None:
            checks.integer("--N", args.N, 16, 10**6)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", SolitonWarning)
        try:
            sol = soliton(mat, args.case, k, amplitude, args.kind, theory=theory)
        except ValueError as exc:
            raise ValueError(f"--kind: {exc}" if args.kind and "kind=" in str(exc)
                             else str(exc)) from None
    if sol.width < 1:  # as a model's soliton: no table of an envelope the lattice lacks
        from .models import narrower_than_a_site

        raise ValueError(narrower_than_a_site(amplitude, sol.width))
    log(f"material: alpha = {mat.alpha:g}, K_s = {mat.K_s:g}, K_theta = {mat.K_theta:g} "
        f"(delta = {mat.delta:.4g}); case {args.case}")
    log(f"carrier:  k = {k:g} rad/site; amplitude {amplitude:g} rad (peak rotation of the "
        + ("soliton)" if sol.kind == "bright" else "background)"))
    if units.seconds_per_T:  # --physical: as coefficients and point say it
        log(f"units:    {units.describe()}")
    log(f"NLS ({args.theory}): omega = {sol.omega:.6g} 1/T, v_g = {sol.v_g:.5g} sites/T, "
        f"g1 = {sol.g1:.4g}, g2 = {sol.g2:.4g}, g = g2/g1 = {sol.g:.4g} -> "
        f"{'focusing' if sol.g > 0 else 'defocusing'}: {sol.kind} soliton")
    for w in caught:
        log(f"warning: {w.message}")
    other, other_sol, why = _other_theory(mat, args.case, k, amplitude, theory)
    if other_sol is None:
        log(f"{other}: no soliton here ({why})")
    elif other_sol.kind != sol.kind:
        log(f"{other}: predicts a {other_sol.kind} soliton instead (g = {other_sol.g:.4g}); "
            "the lattice follows the semi-discrete NLS (docs/solitons.md)")
    run = None
    if args.simulate:
        with warnings.catch_warnings():  # a narrow soliton was reported above
            warnings.simplefilter("ignore", SolitonWarning)
            try:
                run = simulate_soliton(mat, args.case, k, amplitude, sol.kind, theory=theory,
                                       N=args.N, travel=args.travel)
            except RunTooLong as exc:  # its remedies as this command's options
                raise ValueError(exc.advice("--travel", "--amplitude")) from None
            except ValueError as exc:  # 'N = 16 is too short ...' -> '--N 16 is ...'
                from .model_soliton import _as_options

                raise ValueError(_as_options(str(exc))) from None
        sol_ring = run.predicted
        log(f"simulated: N = {run.N} sites, k = {sol_ring.k:.6g} rad/site (the nearest a ring "
            f"carries a {sol.kind} soliton), T = {run.t_end:.6g}, {run.method} dt = "
            f"{run.dt:g}; travelled {run.measured()['travelled_widths']:.3g} widths")
        sol = sol_ring
        if other_sol is not None:  # the other theory at the ring's k too
            other, other_sol, _ = _other_theory(mat, args.case, sol.k, amplitude, theory)
    log(_table(sol, run, other_sol if other_sol is not None and other_sol.kind == sol.kind
               else None, other))
    if run is not None:
        m = run.measured()
        shape = "sech^2" if sol.kind == "bright" else "tanh^2"
        log(f"radiation (intensity shed beyond 6 widths / soliton's): {m['radiation']:.2g}; "
            f"shape off {shape} inside: {m['shape_misfit']:.2g}; drift over the run: width "
            f"{m['drift']['width']:+.2%}, amplitude {m['drift']['amplitude']:+.2%}")
        if sol.case == "coupled" and sol.k * sol.width < KINK_SEPARATION:
            log(f"warning: the envelope spans k x width = {sol.k * sol.width:.2g} rad of "
                f"carrier phase (< {KINK_SEPARATION:g}): the kink (|q| < ~4.5 / width) and the "
                "second harmonic (2k) overlap in wavenumber, so the kink height is not "
                "separable (its measurement low-passes |q| < k/2); a smaller amplitude or a "
                "larger k widens the envelope")
        spread = kink_spread(run)
        if spread > KINK_SPREAD:
            log(f"warning: the measured kink height varies by {spread:.0%} of its mean over "
                "the run (sound in U crossing the +-8-width window, or a ring too short for "
                "it): not a measurement of the kink; a longer ring (--N) may settle it")
    result = soliton_report(sol, run)
    if units.seconds_per_T:  # --physical promises seconds and metres: the table's in SI
        result["si"] = _si(sol, run, units)
        log("in SI: " + "; ".join(f"{name} " + ", ".join(f"{key} {v:.4g} {SI_UNITS[key]}"
                                                         for key, v in values.items())
                                  for name, values in result["si"].items()))
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        png = _figure(sol, run)
        write_results({out / "soliton.json": json.dumps(strict_json(result), indent=2) + "\n",
                       out / "soliton.png": png})
        log(f"wrote {out / 'soliton.json'} and {out / 'soliton.png'}")
    return result


def _figure(sol, run) -> bytes:
    """soliton.png's bytes: profile, kink and trajectory against the prediction."""
    from scenes import plt, soliton_figure

    fig = soliton_figure(sol, run)
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return buf.getvalue()


#: the kink is measured by low-passing the strain at |q| < k/2; a sech^2 kink of width w
#: keeps 99% of its spectrum below 4.5 / w, so k w >= 9 separates it from the harmonic
KINK_SEPARATION = 9.0
#: the kink height measured over a run may vary by this fraction of its mean (the
#: README's soliton: 0.4%) before it is called no measurement
KINK_SPREAD = 0.1


def kink_spread(run) -> float:
    """(max - min) / |mean| of the kink height over a run's snapshots (0 in case I)."""
    if run.predicted.case != "coupled":
        return 0.0
    h = run.series("kink_height")
    return float((h.max() - h.min()) / abs(h.mean())) if h.mean() else float("inf")


def _table(sol, run, other_sol, other_name) -> str:
    head = ["quantity", f"predicted ({sol.theory})"]
    if other_sol is not None:
        head.append(other_name)
    if run is not None:
        head += ["measured", "error"]
    head.append("unit")
    pred = sol.summary()
    meas = run.measured() if run is not None else {}
    alt = other_sol.summary() if other_sol is not None else {}
    rows = [head]
    for key, unit in ROWS:
        if key == "kink_height" and sol.case == "rotation":
            continue
        row = [key.replace("_", " "), f"{pred[key]:.6g}"]
        if other_sol is not None:
            row.append(f"{alt[key]:.6g}")
        if run is not None:
            err = meas[key] / pred[key] - 1 if pred[key] else float("nan")
            row += [f"{meas[key]:.6g}", f"{err:+.2%}"]
        row.append(unit)
        rows.append(row)
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join([f"kind: {sol.kind}"] + lines)
