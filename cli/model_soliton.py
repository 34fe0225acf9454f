"""`flexmm soliton --model ... --simulate` (and `--out` without it): any model's NLS soliton
launched on a ring and tracked, the same table as the paper chain's (cli.soliton): velocity,
width, amplitude, frequency and the kink of every field that has a mean flow, predicted
beside measured; soliton.json and soliton.png under --out."""

from __future__ import annotations

import json
import math
from pathlib import Path


def _rows(pred, fields, units):
    """(key, label, unit) of the table's rows."""
    carrier = fields[pred.nls.carrier.field]
    rows = [("velocity", "velocity", "sites/time"), ("width", "width", "sites"),
            ("amplitude", "amplitude", f"first harmonic of {carrier}"),
            ("frequency", "frequency", "1/time")]
    for i in pred.kink_fields():
        rows.append((f"kink_{fields[i]}", f"kink of {fields[i]}",
                     f"{fields[i]}, lattice units"))
    return rows


def table(pred, run, fields, units) -> str:
    """The paper chain's layout: quantity, predicted, measured, error, unit."""
    head = ["quantity", "predicted (semi-discrete NLS)"]
    if run is not None:
        head += ["measured", "error"]
    head.append("unit")
    p = pred.summary(fields)
    m = run.measured() if run is not None else {}
    kinds = {"velocity": "velocity", "width": "length", "frequency": "rate"}
    rows = [head]
    for key, label, unit in _rows(pred, fields, units):
        row = [label, f"{p[key]:.6g}"]
        if run is not None:
            err = m[key] / p[key] - 1 if p[key] else math.nan
            row += [f"{m[key]:.6g}", f"{err:+.2%}"]
        row.append(unit + (units.si(p[key], kinds[key]) if key in kinds else ""))
        rows.append(row)
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join([f"kind: {pred.kind}"] + lines)


def with_units(report: dict, units) -> dict:
    """``report`` with its "units" (and "si") objects: the relative numbers (errors, the
    measured drifts) kept out of the scaling, which goes by key name."""
    from .units import add_units

    plain = {key: value for key, value in report.items() if key != "errors"}
    measured = report.get("measured")
    if measured:
        plain["measured"] = {key: v for key, v in measured.items() if key != "drift"}
    scaled = add_units(plain, units)
    out = dict(report)
    out["units"] = scaled["units"]
    if "si" in scaled:
        out["si"] = scaled["si"]
    return out


def _estimate(args, model, branch) -> None:
    """Say what the run will cost before it starts (one short run of the ring measured
    here, ``numerics.maps.estimate_model_point``): a soliton a few hundred sites wide needs
    a ring of thousands and a long T, minutes of silence otherwise."""
    import sys

    from common.text import duration
    from energy import ModelError
    from numerics.maps import estimate_model_point
    from numerics.models import check_soliton_launch, ring_soliton, travel_time

    try:
        pred = ring_soliton(model, args.k, args.amplitude, N=args.N, kind=args.kind,
                            branch=branch)
        check_soliton_launch(model, pred, args.k)  # refused before its estimate
        # a run too long is refused before it too: the estimate's own short run on its
        # ring (567 692 sites at fput, k = 1, amplitude 3e-5) took minutes first
        t_end = travel_time(pred, args.travel)
        est = estimate_model_point(model, pred.k, args.amplitude, pred.nls.carrier.branch,
                                   N=pred.N, seeds=1, t_end=t_end, figure=bool(args.out))
    except ModelError:
        return  # what the run refuses, it says itself in one line
    hint = ("; a larger --amplitude narrows the soliton (width ~ 1/amplitude): a shorter "
            "ring and run" if est.seconds > 60 else "")
    print(f"estimate: about {duration(est.seconds)} (a ring of N = {pred.N} sites, soliton "
          f"{pred.width:.3g} sites wide, T = {t_end:.4g} for {args.travel:g} widths; one run "
          f"measured here){hint}", file=sys.stderr if args.json else sys.stdout, flush=True)


def _as_options(text: str) -> str:
    """An error of ``simulate_soliton`` with its arguments named as this command's
    options ('kind dark: ...' -> '--kind dark: ...', 'N = 16 is ...' -> '--N 16 is ...',
    '...: N = 5112 holds' -> '...: --N 5112 holds')."""
    import re

    text = re.sub(r"^kind (\w+):", r"--kind \1:", text)
    # 'give travel <= 1.5, or amplitude >= 3e-4' (the API's names: travel_time, soliton_ring)
    text = re.sub(r"(?<![-\w])(travel|amplitude) (<=|>=) ", r"--\1 \2 ", text)
    text = re.sub(r"^amplitude (?=[\d.])", "--amplitude ", text)
    return re.sub(r"(^|: |; )N = (\d+) ", r"\1--N \2 ", text)  # and the ring it advises


def lossy_note(model, k: float, branch, units) -> tuple[float, str | None]:
    """(the carrier's amplitude decay rate, a note) of a lossy model's soliton: the NLS's
    soliton is lossless, the chain's decays (0.0 and None without losses)."""
    from numerics.models import carrier_damping

    damping = carrier_damping(model, k, branch)
    if not damping > 0:
        return 0.0, None
    return damping, (f"note: {model.name} has [dissipation]: the carrier's amplitude decays "
                     f"at {damping:.4g} /time{units.si(damping, 'rate')} (e-folding "
                     f"{1 / damping:.4g} time{units.si(1 / damping, 'time')}), which this "
                     f"soliton of the lossless NLS leaves out; {lossless_params(model)} for "
                     "the lossless chain")


def lossless_params(model) -> str:
    """The options that make a lossy ``model`` lossless: '--param gamma=0' for each
    parameter its [dissipation] uses (a remedy the user can type)."""
    from numerics.maps import damping_parameters

    names = damping_parameters(model.lattice)
    return (" ".join(f"--param {n}=0" for n in names) if names
            else "--param each damping parameter = 0")


def run_model_soliton(args, model, units, branch) -> dict:
    """Predict (and with --simulate, run) the soliton; print; write --out. Returns the
    report (``numerics.models.soliton_report``)."""
    from common.output import prepare_output
    from numerics.lattice import checks
    from numerics.models import ring_soliton, simulate_soliton, soliton_report

    from .models import _emit

    folder = prepare_output(args.out, cache=False) if args.out else None
    run = None
    if args.simulate:
        if model.lossy and any(m.any() for m in model.damping):
            # the launch refuses it (check_soliton_launch); said here with the options
            raise ValueError(f"--simulate: model {model.describe()} has [dissipation]: its "
                             "soliton decays, and the NLS it is measured against is "
                             f"lossless; add {lossless_params(model)} to launch the "
                             "lossless one")
        from numerics.models import MIN_TRAVEL  # below it the velocity is round-off

        checks.real("--travel", args.travel, MIN_TRAVEL, 1000.0, low_open=False)
        if args.N is not None:
            checks.integer("--N", args.N, 16, 10**6)
        _estimate(args, model, branch)
        try:
            run = simulate_soliton(model, args.k, args.amplitude, args.kind, branch=branch,
                                   N=args.N, travel=args.travel)
        except ValueError as exc:  # the API's argument names, said as the options are
            raise ValueError(_as_options(str(exc))) from None
        pred = run.predicted
    else:
        try:
            pred = ring_soliton(model, args.k, args.amplitude, kind=args.kind, branch=branch)
        except ValueError as exc:
            raise ValueError(_as_options(str(exc))) from None
    report = soliton_report(pred, run)
    damping, lossy = lossy_note(model, pred.k, pred.nls.carrier.branch, units)
    if damping > 0:  # a lossy model's soliton was printed as if it lasted
        report["carrier_damping"] = damping
    if not args.json:
        from numerics.models import nls

        asked = nls(model, args.k, pred.nls.carrier.branch)  # the ring's k comes below
        c = asked.carrier
        print(f"model:    {model.describe()}")
        print(f"carrier:  k = {args.k:g} rad/site{units.si(args.k, 'wavenumber')} on branch "
              f"{c.branch}, omega = {c.omega:.6g}; g1 = {asked.g1:.6g}, g2 = "
              f"{asked.g2:.6g}, g = g2/g1 = {asked.g:.4g} -> "
              f"{'focusing' if asked.g > 0 else 'defocusing'}: {pred.kind} soliton")
        print(f"units:    {units.describe()}")
        if run is not None:
            m = run.measured()
            print(f"simulated: N = {run.N} sites, k = {pred.k:.6g} rad/site (the nearest a "
                  f"ring carries a {pred.kind} soliton), T = {run.t_end:.6g}, {run.method} "
                  f"dt = {run.dt:.4g}; travelled {m['travelled_widths']:.3g} widths; "
                  f"energy drift {m['energy_drift']:.2g}")
        else:
            print(f"predicted on a ring of N = {pred.N} sites (k = {pred.k:.6g}); "
                  "--simulate measures it")
        print(table(pred, run, model.fields, units))
        if run is not None:
            m = run.measured()
            shape = "sech^2" if pred.kind == "bright" else "tanh^2"
            print(f"radiation (intensity shed beyond 6 widths / soliton's): "
                  f"{m['radiation']:.2g}; shape off {shape} inside: {m['shape_misfit']:.2g}; "
                  f"drift over the run: width {m['drift']['width']:+.2%}, amplitude "
                  f"{m['drift']['amplitude']:+.2%}")
        for line in pred.notes():
            print(line)
        if lossy:
            print(lossy)
    if folder is not None:
        from common.files import write_results
        from common.output import strict_json

        png = _figure(pred, run, model)
        write_results({folder / "soliton.json":
                       json.dumps(strict_json(with_units(report, units)), indent=2) + "\n",
                       Path(folder) / "soliton.png": png})
        if not args.json:
            print(f"wrote {folder / 'soliton.json'} and {folder / 'soliton.png'}")
    if args.json:  # after the files, which it names (as a map's --json): stdout holds no line
        _emit(with_units(report, units) | ({"files": [str(folder / "soliton.json"),
                                                      str(folder / "soliton.png")]}
                                           if folder is not None else {}))
    return report


def _figure(pred, run, model) -> bytes:
    """soliton.png's bytes: (a) the carrier's first harmonic against the predicted envelope, (b) the
    kink fields' mean displacement, (c) the trajectory against v_g t."""
    import numpy as np

    from scenes import plt

    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), layout="constrained")
    N, w = pred.N, pred.width
    span = min(8 * w, N / 2)
    n = np.arange(N)
    f = pred.nls.carrier.field
    fields = model.fields
    u0, v0 = pred.state()
    if run is not None:
        last = run.snapshots[-1]
        u_last = run.fields[-1]
        # the velocities are not kept: the band-passed displacement alone (Re z)
        z = pred.carrier_signal(u_last, np.zeros_like(u_last))
        xi = (n - last.centre + N / 2) % N - N / 2
        keep = np.argsort(xi)
        keep = keep[np.abs(xi[keep]) < span]
        axes[0].plot(xi[keep], 2 * np.real(z[keep]), ".", ms=2, color="0.5",
                     label=f"{fields[f]} (first harmonic) at T = {last.t:.4g}")
    xs = np.linspace(-span, span, 801)
    env = 2 * np.abs(pred.envelope(xs))
    axes[0].plot(xs, env, "C3-", lw=1.2, label=r"predicted envelope $\pm 2|E|$")
    axes[0].plot(xs, -env, "C3-", lw=1.2)
    axes[0].set(xlabel="site from the centre", ylabel=fields[f],
                title=f"(a) {pred.kind} soliton: profile", xlim=(-span, span))
    if pred.kind == "bright":  # room above the peak for the legend
        axes[0].set_ylim(-1.1 * env.max(), 1.6 * env.max())
    axes[0].legend(fontsize=7, loc="upper right" if pred.kind == "bright" else "lower right")
    ax = axes[1]
    kinks = pred.kink_fields()
    q = 2 * np.pi * np.fft.rfftfreq(N)

    def mean_part(x):  # |q| < k/2: the mean flow without the carrier and its harmonic
        h = np.fft.rfft(x)
        h[q > pred.k / 2] = 0
        return np.fft.irfft(h, N)

    d0 = n - N / 2
    sel0 = np.abs(d0) < span
    for j, i in enumerate(kinks):
        mp = mean_part(u0[i])[sel0]
        ax.plot(d0[sel0], mp - mp[0], f"C{j}-", lw=1.2,
                label=f"{fields[i]} predicted (kink {pred.soliton.kink[i]:.3g})")
        if run is not None:
            d = (n - last.centre + N / 2) % N - N / 2
            order = np.argsort(d)
            sel = order[np.abs(d[order]) < span]
            mm = mean_part(run.fields[-1][i])[sel]
            ax.plot(d[sel], mm - mm[0], ".", ms=2, color=f"C{j}",
                    label=f"{fields[i]} measured (kink {last.kink[i]:.3g})")
    if kinks:
        ax.legend(fontsize=7)
    else:
        ax.text(0.5, 0.5, "no acoustic field: no kink", transform=ax.transAxes, ha="center")
    ax.set(xlabel="site from the centre", ylabel="mean displacement (|q| < k/2)",
           title="(b) kink", xlim=(-span, span))
    ax = axes[2]
    if run is not None:
        t, c = run.t, run.series("centre")
        ax.plot(t, c - c[0], "o", ms=3, color="0.3",
                label=f"measured (v = {run.velocity:.4g} sites/time)")
        ax.plot(t, pred.velocity * t, "C3-", lw=1.2,
                label=f"predicted v_g t (v_g = {pred.velocity:.4g})")
    else:
        t = np.linspace(0, 20 * w / max(abs(pred.velocity), 1e-12), 50)
        ax.plot(t, pred.velocity * t, "C3-", lw=1.2,
                label=f"predicted (v_g = {pred.velocity:.4g} sites/time)")
        ax.text(0.05, 0.85, "no run: --simulate measures it", transform=ax.transAxes,
                fontsize=8)
    ax.legend(fontsize=7, loc="lower right")
    ax.set(xlabel="time (lattice units)", ylabel="centre moved (sites)",
           title="(c) trajectory")
    fig.suptitle(f"{model.describe()}; k = {pred.k:.6g}, amplitude {pred.soliton.amplitude:g}"
                 f"; semi-discrete NLS; ring N = {N}", fontsize=9)
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return buf.getvalue()
