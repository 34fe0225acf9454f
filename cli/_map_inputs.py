"""What a map was asked for, as its summary.json says it (``inputs``): the command's
inputs, so that a summary alone tells which map it summarises (the store's attributes say
it too, for a user who has the store)."""

from __future__ import annotations


def _floats(values) -> list:
    return [float(v) for v in values]


def paper_inputs(args, params, device: str) -> dict:
    """The inputs of ``flexmm map`` (the paper chain): material, case, the two axes'
    values (as given: --delta, or --K-theta), amplitude, N, T, seeds, start, device, and
    whether it simulates."""
    rows = "delta" if getattr(args, "delta", None) is not None else "K_theta"
    return {"command": "flexmm map", "case": params.case, "alpha": float(params.alpha),
            "K_s": float(params.K_s),
            "axes": {rows: _floats(getattr(params, rows)), "k": _floats(params.k)},
            "k_simulated": _floats(params.k_simulated),
            "amplitude": float(params.amplitude), "N": int(params.N),
            "t_end": float(params.t_end), "seeds": int(params.seeds), "start": params.start,
            "theory_only": bool(params.theory_only), "device": device,
            "block": int(params.block)}


def model_inputs(params, model, device: str) -> dict:
    """The inputs of ``flexmm map --model``: the model and its fixed parameters, the two
    axes' values, k (where fixed), amplitude (null where it is an axis), branch, N (null
    without the ring), T (null: each cell's from its rate, ``t_end_rule``), seeds, start,
    device, and the --exact and --theory-only flags."""
    axes = {params.rows[0]: _floats(params.rows[1]), params.cols[0]: _floats(params.cols[1])}
    simulated = not params.theory_only
    out = {"command": "flexmm map --model", "model": model.name,
           "parameters": {n: float(v) for n, v in model.params.items() if n not in axes},
           "axes": axes, "k": None if params.k is None else float(params.k),
           "amplitude": None if params.amplitude is None else float(params.amplitude),
           "branch": params.branch, "N": int(params.N) if params.ring else None,
           "t_end": None if params.t_end is None or not simulated else float(params.t_end),
           "seeds": int(params.seeds) if simulated else None, "start": params.start,
           "exact": bool(params.exact), "theory_only": bool(params.theory_only),
           "device": device, "block": int(params.block)}
    if simulated and params.t_end is None:
        out["t_end_rule"] = "each cell's runs as long as its exact rate needs (run_length)"
    return out


__all__ = ["paper_inputs", "model_inputs"]
