"""Any model's ring on a GPU (numba's CUDA target): its generated site force compiled for
the device, one CUDA block per chain.

The device source is printed from the model's generated module (``generated/models/NAME.py``
or a user model's cached module), never from the model file: the bodies of
``site_functions_all`` and ``accelerations_into`` are parsed (``ast``), checked against a
whitelist (assignments of arithmetic on names, numbers, the arrays ``_u``, ``_F``, ``_p``
and the elementary functions the energy grammar allows; no import, no attribute but
``numpy.<function>``, no call but those functions) and cut into three per-site device
functions, the same operations in the same order as the CPU's loop:

- ``_site_functions(_u, _F, _p, _n, _N)``: the loop body of ``site_functions_all`` for site
  ``_n`` (sin and cos by the fused kernel's polynomial, as ``numerics.models`` compiles it
  on the CPU when every field is within TRIG_LIMIT);
- ``_site_force(_u, _F, _p, _n, _N, _acc, _r)``: site ``_n``'s accelerations into
  ``_acc[a * PER_THREAD + _r]``: the bond (n - 1, n) leaves its pull on n (the loop body at
  n - 1, as the CPU's previous iteration), the bond (n, n + 1) and the site's own term give
  the accelerations (the loop body at n); site 0 starts from the CPU's wrap bond, site
  N - 1 ends with its epilogue.

Arrays on the device are flat: ``_u[a, n]`` is printed ``_u[a * _N + n]``. A field or
parameter name reaches this source only as the generated module spells it, a name the
energy parser checked (``energy._spec``); numbers only as ``repr`` of the generated literal.

The kernel (:func:`model_kernel`) advances chain ``blockIdx.x`` with a symplectic RKN method
(the CPU's loop of ``numerics.models.simulate_model``: kick, drift where a != 0, force;
the force evaluation at the end of a step reused at the start of the next) and records,
every ``every`` steps, the spectrum of the deviation from the exact travelling wave: the
wave's profile at the record's time is summed on the chip from its Fourier coefficients,
the deviation kept in shared memory, its DFT taken over the ring (one bin a thread in
turn, the bins 0..N/2 of the real fields) and sqrt(sum over fields |DFT|^2) / N written to
``spectra[chain, record]``: the per-record row the CPU keeps, from which the host measures
the growth with the CPU's ``measure_growth``. Nothing else leaves the chip; the state
never does.

Layout of a block (``threads`` threads, site i owned by thread i mod threads): shared
memory (dynamic) holds the positions (d N), the site functions (n_f N), the deviation
(d N) and a flag; the velocities and accelerations of a thread's own sites are in local
arrays. A chain whose position leaves the polynomial's range (models with sin/cos) or
turns non-finite stops with status BAD: the host runs it again on the CPU.
"""

from __future__ import annotations

import ast
import inspect
import math
import textwrap

import numpy as np
from numba import cuda, float64

from ._kernels import TRIG_LIMIT, _sincosvers

#: sites a thread owns at most (as the flexMM kernel)
PER_THREAD = 8
#: threads per block on a GPU (a power of two)
THREADS = 128
#: shared memory a block gets without opting in (bytes)
SHARED_LIMIT = 48 * 1024
#: statuses of a chain
STATUS_OK, STATUS_BAD = 0.0, 1.0

#: the energy grammar's functions (``energy._spec.FUNCTIONS``) as the generated module
#: prints them -> their device form (sin/cos of the site functions: the polynomial)
_DEVICE_FUNCTIONS = {"sin": "math.sin", "cos": "math.cos", "tan": "math.tan",
                     "exp": "math.exp", "log": "math.log", "sqrt": "math.sqrt",
                     "sinh": "math.sinh", "cosh": "math.cosh", "tanh": "math.tanh",
                     "arctan": "math.atan", "abs": "abs", "maximum": "max"}
_ARRAYS = ("_u", "_F", "_p", "_out")
_ALLOWED_NODES = (ast.Module, ast.FunctionDef, ast.arguments, ast.arg, ast.Expr,
                  ast.Assign, ast.Name, ast.Load, ast.Store, ast.Constant, ast.BinOp,
                  ast.UnaryOp, ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow, ast.USub,
                  ast.UAdd, ast.Call, ast.Attribute, ast.Subscript, ast.Tuple, ast.For,
                  ast.If, ast.Compare, ast.Eq, ast.Return, ast.Pass)


class DeviceSourceError(ValueError):
    """The generated module holds something the device printer does not take."""


def _check(tree: ast.AST, where: str) -> None:
    """Refuse any construct outside the generated force's grammar (see the module)."""
    for node in ast.walk(tree):
        if not isinstance(node, _ALLOWED_NODES):
            raise DeviceSourceError(f"{where}: {type(node).__name__} is not in the generated "
                                    "force's grammar")
        if isinstance(node, ast.Constant) and not isinstance(node.value, (int, float, str)):
            raise DeviceSourceError(f"{where}: constant {node.value!r}")
        if isinstance(node, ast.Constant) and isinstance(node.value, bool):
            raise DeviceSourceError(f"{where}: constant {node.value!r}")
        if isinstance(node, ast.Attribute):
            ok = (isinstance(node.value, ast.Name)
                  and ((node.value.id == "numpy" and node.attr in _DEVICE_FUNCTIONS)
                       or (node.value.id == "_u" and node.attr == "shape")))
            if not ok:
                raise DeviceSourceError(f"{where}: attribute {ast.unparse(node)}")
        if isinstance(node, ast.Call):
            f = node.func
            ok = (isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name)
                  and f.value.id == "numpy") or (isinstance(f, ast.Name) and f.id == "range")
            if not ok or node.keywords:
                raise DeviceSourceError(f"{where}: call {ast.unparse(node)}")
        if isinstance(node, ast.Name) and not node.id.isidentifier():
            raise DeviceSourceError(f"{where}: name {node.id!r}")


def _parse(f, where: str) -> ast.FunctionDef:
    tree = ast.parse(textwrap.dedent(inspect.getsource(f)))
    _check(tree, where)
    fn = tree.body[0]
    if not isinstance(fn, ast.FunctionDef):
        raise DeviceSourceError(f"{where}: not a function")
    # the docstring goes
    body = [s for s in fn.body if not (isinstance(s, ast.Expr)
                                       and isinstance(s.value, ast.Constant))]
    fn.body = body
    return fn


def _mentions(node: ast.AST, names) -> bool:
    return any(isinstance(n, ast.Name) and n.id in names for n in ast.walk(node))


class _Device(ast.NodeTransformer):
    """Flat indices, the site's neighbours, the device's functions.

    ``index``: the name that replaces ``_n`` (and ``_n + 1`` -> ``plus``); ``trig``: the
    device spelling of sin and cos; ``out``: what ``_out[a, _n] = x`` becomes (None: the
    statement is dropped; "acc": ``_acc[a * PER_THREAD + _r] = x``; "F": kept for _F)."""

    def __init__(self, index: str, plus: str, trig: dict, out: str | None):
        self.index, self.plus, self.trig, self.out = index, plus, trig, out

    def _site(self, node):
        # _n -> index, _n + 1 -> plus, _N - 1 stays
        if isinstance(node, ast.Name) and node.id == "_n":
            return ast.Name(self.index, ast.Load())
        if (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add)
                and isinstance(node.left, ast.Name) and node.left.id == "_n"
                and isinstance(node.right, ast.Constant) and node.right.value == 1):
            return ast.Name(self.plus, ast.Load())
        return self.visit(node)

    def visit_Subscript(self, node):
        if isinstance(node.value, ast.Name) and node.value.id in ("_u", "_F", "_out"):
            if not (isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2):
                raise DeviceSourceError(f"index {ast.unparse(node)}")
            a, n = node.slice.elts
            a, n = self.visit(a), self._site(n)
            if node.value.id == "_out":
                flat = ast.BinOp(ast.BinOp(a, ast.Mult(), ast.Name("PER_THREAD", ast.Load())),
                                 ast.Add(), ast.Name("_r", ast.Load()))
                return ast.Subscript(ast.Name("_acc", ast.Load()), flat, node.ctx)
            flat = ast.BinOp(ast.BinOp(a, ast.Mult(), ast.Name("_N", ast.Load())), ast.Add(), n)
            return ast.Subscript(ast.Name(node.value.id, ast.Load()), flat, node.ctx)
        return self.generic_visit(node)

    def visit_Call(self, node):
        self.generic_visit(node)
        f = node.func
        if isinstance(f, ast.Attribute) and f.value.id == "numpy":
            name = self.trig.get(f.attr, _DEVICE_FUNCTIONS[f.attr])
            node.func = ast.parse(name, mode="eval").body
        return node


def _stmts(stmts, index, plus, trig, out) -> list:
    """Device copies of ``stmts`` (out None: the _out assignments dropped)."""
    t = _Device(index, plus, trig, out)
    res = []
    for s in stmts:
        if out is None and isinstance(s, ast.Assign) and _mentions(s.targets[0], ("_out",)):
            continue
        res.append(t.visit(ast.parse(ast.unparse(s)).body[0]))
    return res


def _function(name: str, args: list, body: list) -> str:
    """The source of ``def name(args): body`` (name and args: this module's own)."""
    fn = ast.parse(f"def {name}({', '.join(args)}):\n    pass\n").body[0]
    fn.body = body or [ast.Pass()]
    return ast.unparse(ast.fix_missing_locations(ast.Module([fn], type_ignores=[])))


def _split_force(fn: ast.FunctionDef):
    """(constants, wrap, loop body, epilogue) of ``accelerations_into``: the prologue's
    statements before the first that reads ``_u``/``_F`` (the parameters and constants),
    the rest of the prologue (the ring's wrap bond), the bond loop's body, and what
    follows the loop (site N - 1)."""
    loops = [i for i, s in enumerate(fn.body) if isinstance(s, ast.For)]
    if len(loops) != 1:
        raise DeviceSourceError("accelerations_into: one bond loop expected")
    i = loops[0]
    pre = [s for s in fn.body[:i] if not isinstance(s, ast.If)
           and not (isinstance(s, ast.Assign) and isinstance(s.targets[0], ast.Name)
                    and s.targets[0].id == "_N")]
    first = next((j for j, s in enumerate(pre) if _mentions(s, ("_u", "_F"))), len(pre))
    return pre[:first], pre[first:], fn.body[i].body, fn.body[i + 1:]


def device_source(code) -> tuple[str, bool]:
    """(source, trig): the device functions ``_site_functions`` and ``_site_force`` of a
    generated model module ``code`` (see the module), and whether its site functions call
    sin or cos (then a position beyond TRIG_LIMIT stops the chain, as the CPU would leave
    the polynomial)."""
    where = f"model module {getattr(code, '__name__', '?')}"
    sites = _parse(code.site_functions_all, where + ".site_functions_all")
    force = _parse(code.accelerations_into, where + ".accelerations_into")
    params = [s for s in sites.body if not isinstance(s, ast.For)]
    loops = [s for s in sites.body if isinstance(s, ast.For)]
    if len(loops) != 1:
        raise DeviceSourceError(f"{where}.site_functions_all: one site loop expected")
    poly = {"sin": "_psin", "cos": "_pcos"}
    trig = any(isinstance(n, ast.Attribute) and n.attr in ("sin", "cos")
               for n in ast.walk(loops[0]))
    src_sites = _function("_site_functions", ["_u", "_F", "_p", "_n", "_N"],
                          _stmts(params + loops[0].body, "_n", "_n", poly, "F"))
    const, wrap, body, epilogue = _split_force(force)
    args = ["_u", "_F", "_p", "_n", "_N", "_acc", "_r"]
    # site 0: the wrap bond, then the loop body at 0; site N - 1: the wrap bond (its
    # forward pull), the loop body at N - 2 (the pull on N - 1), the epilogue; any other
    # site: the body at n - 1 (its pull on n), the body at n
    lib: dict = {}
    first = _stmts(const + wrap, "_n", "_l", lib, "acc") + _stmts(body, "_n", "_l", lib,
                                                                    "acc")
    last = (_stmts(const + wrap, "_n", "_l", lib, "acc") + _stmts(body, "_m", "_n", lib, None)
            + _stmts(epilogue, "_n", "_l", lib, "acc"))
    inner = (_stmts(const, "_n", "_l", lib, "acc") + _stmts(body, "_m", "_n", lib, None)
             + _stmts(body, "_n", "_l", lib, "acc"))
    parts = [_function(f"_site_force_{name}", args + ["_m", "_l"], stmts)
             for name, stmts in (("first", first), ("last", last), ("inner", inner))]
    return "\n\n\n".join([src_sites, *parts]) + "\n", trig


#: registered device forces: a model's MODEL_HASH (its energy's content hash) ->
#: (name, fields, parameters, builder); builder() -> (site_functions, site_force, n_f) with
#: the generated device functions' signatures. The paper chain's models register the
#: fused flexMM kernel's force (``_cuda``'s ``_acc``, today's GPU kernel's): a model file
#: with the same energy gets it too, any other model its printed force
DEVICE_FORCES: dict = {}


def register_device_force(model_hash: str, name: str, fields: tuple, parameters: tuple,
                          builder) -> None:
    """Register a hand-written device force for the model of ``model_hash`` (its fields
    and parameters in this order, checked at use)."""
    DEVICE_FORCES[model_hash] = (name, tuple(fields), tuple(parameters), builder)


def device_force_of(code, fast: bool = True):
    """(name, n_f): the device force a generated module's kernel uses, "generated" or a
    registered one (``DEVICE_FORCES``; ``fast`` False: always the generated), and the site
    functions it keeps per site (shared memory)."""
    entry = DEVICE_FORCES.get(getattr(code, "MODEL_HASH", None)) if fast else None
    if entry is not None and (tuple(code.FIELDS), tuple(code.PARAMETERS)) == entry[1:3]:
        return entry[0], 3
    return "generated", int(code.SITE_FUNCTIONS_ALL)


def _fused_flexmm(coupled: bool):
    """The fused flexMM kernel's site force (``_cuda``: eq. `norm`, theta's acceleration
    with alpha^2, U's) behind the generated functions' signatures: F holds sin, cos and
    1 - cos of theta (the polynomial), p = (alpha, K_s, K_theta)."""
    from ._cuda import _acc_d, _sincosvers_d

    @cuda.jit(device=True)
    def functions(u, F, p, n, N):
        s, c, v = _sincosvers_d(u[n])
        F[n] = s
        F[N + n] = c
        F[2 * N + n] = v

    @cuda.jit(device=True)
    def force(u, F, p, n, N, acc, r, m, l):
        U = u[N:2 * N] if coupled else u[0:N]  # case I never reads U
        at, aU = _acc_d(n, m, l, u[0:N], U, F[0:N], F[N:2 * N], F[2 * N:3 * N], coupled,
                        p[0] * p[0], p[1], p[2])
        acc[r] = at
        if coupled:
            acc[PER_THREAD + r] = aU

    return functions, force, 3


def _register_builtin() -> None:
    from generated.models import flexmm, flexmm_rotation

    for mod, coupled in ((flexmm, True), (flexmm_rotation, False)):
        register_device_force(mod.MODEL_HASH, f"fused flexMM ({mod.NAME})", mod.FIELDS,
                              mod.PARAMETERS, lambda c=coupled: _fused_flexmm(c))


_register_builtin()

_BUILT: dict = {}


def model_kernel(code, fast: bool = True):
    """(kernel, trig) for a generated model module: the CUDA kernel of its chains (compiled
    on first launch) and whether a position beyond TRIG_LIMIT stops a chain (its site
    functions' sin/cos are the polynomial). ``fast``: a registered device force where the
    model has one (``device_force_of``). Cached per module hash."""
    force_name, nf = device_force_of(code, fast)
    key = (code.__name__, code.MODEL_HASH, force_name)
    if key in _BUILT:
        return _BUILT[key]
    if force_name != "generated":
        site_functions, f_first, nf = DEVICE_FORCES[code.MODEL_HASH][3]()
        f_last = f_inner = f_first
        trig = True
    else:
        src, trig = device_source(code)
        sincos = cuda.jit(device=True)(_sincosvers.py_func)

        def _psin(x):
            return sincos(x)[0]

        def _pcos(x):
            return sincos(x)[1]

        ns = {"math": math, "PER_THREAD": PER_THREAD, "_psin": cuda.jit(device=True)(_psin),
              "_pcos": cuda.jit(device=True)(_pcos)}
        exec(compile(src, f"<device force of {code.__name__}>", "exec"), ns)
        site_functions = cuda.jit(device=True)(ns["_site_functions"])
        f_first = cuda.jit(device=True)(ns["_site_force_first"])
        f_last = cuda.jit(device=True)(ns["_site_force_last"])
        f_inner = cuda.jit(device=True)(ns["_site_force_inner"])
    D = len(code.FIELDS)
    NF = max(nf, 1)
    HAS_F = nf > 0
    LOCAL = D * PER_THREAD
    CHECK = bool(trig)
    LIMIT = TRIG_LIMIT

    @cuda.jit(device=True)
    def forces(u, F, p, acc, t, bs, n):
        for r in range(PER_THREAD):
            i = t + r * bs
            if i < n:
                if i == 0:
                    f_first(u, F, p, i, n, acc, r, n - 1, 1)
                elif i == n - 1:
                    f_last(u, F, p, i, n, acc, r, n - 2, 0)
                else:
                    f_inner(u, F, p, i, n, acc, r, i - 1, i + 1)

    @cuda.jit(device=True)
    def functions(u, F, p, t, bs, n):
        """The site functions of the thread's sites; 1 when a position is out of range."""
        bad = 0
        for r in range(PER_THREAD):
            i = t + r * bs
            if i < n:
                for a in range(D):
                    x = u[a * n + i]
                    if CHECK:
                        bad += 0 if abs(x) <= LIMIT else 1
                    elif not math.isfinite(x):
                        bad += 1
                if HAS_F:
                    site_functions(u, F, p, i, n)
        return bad

    @cuda.jit
    def kernel(u0, v0, params, dts, nsteps, every, acoef, bcoef, k, omega, cre, cim,
               cos_t, sin_t, spectra, status):
        """Chain ``blockIdx.x``: u0, v0 (chains, d N) flat; params (chains, P) (the
        generated force divides by the masses itself); dts, nsteps, every per chain;
        k, omega, cre, cim (chains, d, 2H + 1) the exact wave; spectra (chains, records,
        N/2 + 1) out; status (chains, 2) out: (STATUS_*, records taken)."""
        chain = cuda.blockIdx.x
        t = cuda.threadIdx.x
        bs = cuda.blockDim.x
        n = u0.shape[1] // D
        p = params[chain]
        dt = dts[chain]
        ns = nsteps[chain]
        ev = every[chain]
        kk = k[chain]
        om = omega[chain]
        nh = cre.shape[2]
        H = (nh - 1) // 2
        nq = n // 2 + 1
        nst = acoef.size

        sh = cuda.shared.array(0, dtype=float64)
        u = sh[0:D * n]
        F = sh[D * n:(D + NF) * n]
        dev = sh[(D + NF) * n:(2 * D + NF) * n]
        flag = sh[(2 * D + NF) * n:(2 * D + NF) * n + 1]

        w = cuda.local.array(LOCAL, float64)
        acc = cuda.local.array(LOCAL, float64)
        prof = cuda.local.array(D, float64)
        for r in range(PER_THREAD):
            i = t + r * bs
            for a in range(D):
                acc[a * PER_THREAD + r] = 0.0
                w[a * PER_THREAD + r] = 0.0
                if i < n:
                    u[a * n + i] = u0[chain, a * n + i]
                    w[a * PER_THREAD + r] = v0[chain, a * n + i]
        if t == 0:
            flag[0] = 0.0
        cuda.syncthreads()
        bad = functions(u, F, p, t, bs, n)
        cuda.syncthreads()
        forces(u, F, p, acc, t, bs, n)
        done = 0
        rec = 0
        while True:
            # the record at step ``done``: the deviation from the wave at t = done dt
            if bad:
                flag[0] = 1.0
            cuda.syncthreads()
            if flag[0] != 0.0:
                break
            tr = done * dt
            for r in range(PER_THREAD):
                i = t + r * bs
                if i < n:
                    # U_a(xi) = Re sum_h c[a, h] e^{i h xi}: cos(h xi), sin(h xi) by the
                    # angle-addition recurrence (its error grows as h eps, on harmonics
                    # whose size falls as a^h)
                    xi = kk * i - om * tr
                    c1 = math.cos(xi)
                    s1 = math.sin(xi)
                    for a in range(D):
                        prof[a] = cre[chain, a, H]
                    ch = 1.0
                    sh_ = 0.0
                    for h in range(1, H + 1):
                        ch, sh_ = ch * c1 - sh_ * s1, sh_ * c1 + ch * s1
                        for a in range(D):
                            prof[a] += ((cre[chain, a, H + h] + cre[chain, a, H - h]) * ch
                                        - (cim[chain, a, H + h] - cim[chain, a, H - h]) * sh_)
                    for a in range(D):
                        dev[a * n + i] = u[a * n + i] - prof[a]
            cuda.syncthreads()
            for q in range(t, nq, bs):
                tot = 0.0
                for a in range(D):
                    re = 0.0
                    im = 0.0
                    idx = 0
                    for j in range(n):
                        x = dev[a * n + j]
                        re += x * cos_t[idx]
                        im -= x * sin_t[idx]
                        idx += q
                        if idx >= n:
                            idx -= n
                    tot += re * re + im * im
                spectra[chain, rec, q] = math.sqrt(tot) / n
            rec += 1
            if done >= ns:
                break
            chunk = min(ev, ns - done)
            for _step in range(chunk):
                for st in range(nst):
                    hb = bcoef[st] * dt
                    for r in range(PER_THREAD):
                        for a in range(D):
                            w[a * PER_THREAD + r] += hb * acc[a * PER_THREAD + r]
                    if acoef[st] != 0.0:
                        ha = acoef[st] * dt
                        cuda.syncthreads()  # every neighbour's read of u done
                        for r in range(PER_THREAD):
                            i = t + r * bs
                            if i < n:
                                for a in range(D):
                                    u[a * n + i] += ha * w[a * PER_THREAD + r]
                        # a site's functions read its own fields only (no barrier before)
                        bad += functions(u, F, p, t, bs, n)
                        cuda.syncthreads()
                        forces(u, F, p, acc, t, bs, n)
            done += chunk
            cuda.syncthreads()  # the record's deviation array is free again
        if t == 0:
            status[chain, 0] = STATUS_BAD if flag[0] != 0.0 else STATUS_OK
            status[chain, 1] = rec

    _BUILT[key] = (kernel, trig)
    return _BUILT[key]


def shared_bytes(d: int, n_functions: int, N: int) -> int:
    """Dynamic shared memory of one chain: positions, site functions, deviation, a flag."""
    return 8 * ((2 * d + max(n_functions, 1)) * N + 1)


def fits(d: int, n_functions: int, N: int) -> str | None:
    """None where a chain of N sites fits one block, else why not (one line)."""
    need = shared_bytes(d, n_functions, N)
    if N > PER_THREAD * THREADS:
        return (f"N = {N} sites is over the {PER_THREAD * THREADS} a block holds "
                f"({THREADS} threads x {PER_THREAD} sites)")
    if need > SHARED_LIMIT:
        return (f"a chain of {d} fields x {N} sites needs {need} bytes of shared memory, "
                f"over the {SHARED_LIMIT} a block gets")
    return None


def twiddles(N: int) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of 2 pi j / N, j = 0 .. N - 1 (the DFT's table)."""
    j = np.arange(N)
    return np.cos(2 * np.pi * j / N), np.sin(2 * np.pi * j / N)


def threads_for(N: int, simulated: bool = False) -> int:
    """Threads per block: THREADS on a GPU; under the simulator the fewest powers of two
    that hold N in PER_THREAD sites each (every thread is a Python thread)."""
    if not simulated:
        return THREADS
    bs = 1
    while bs * PER_THREAD < N:
        bs *= 2
    return bs


__all__ = ["model_kernel", "device_source", "device_force_of", "register_device_force",
           "DEVICE_FORCES", "shared_bytes", "fits", "twiddles",
           "threads_for", "DeviceSourceError", "PER_THREAD", "THREADS", "SHARED_LIMIT",
           "STATUS_OK", "STATUS_BAD"]
