"""The Hill problem of every Bloch family of a chain about one state, for the linear
response (``_response.predict_growth``): the families' modes (eigenvalues, right
eigenvectors), which row deposits each lattice bin, the noise's data on the rows, and the
rows' complex amplitudes at the record times."""

from __future__ import annotations

import numpy as np

from ._quasiperiodic import hill_matrix
from ._torus import uniform_phases

#: largest exponent Re(lambda) t evaluated (e^600 ~ 1e260: the factor of a mode long
#: past saturation; keeps every product finite)
MAX_EXPONENT = 600.0


class Families:
    """The Hill problem of every Bloch family of a chain of N sites about one state."""

    def __init__(self, torus, material, case, m0, N, P, R):
        self.N, self.m0 = N, m0
        # offsets j = 1 .. m0 (q = 2 pi j / N); j and -j are complex conjugates (the
        # fields are real), j = 0 is the carrier's own family (phase, amplitude: neutral)
        self.j = np.arange(1, m0 + 1)
        q = 2 * np.pi * self.j / N
        A, labels, nx, freq = hill_matrix(torus, material, case, q, P, R)
        self.labels, self.nx, self.freq = labels, nx, freq
        self.n = labels.shape[0]
        self.lam, self.V = np.linalg.eig(A)
        # a family's data sit on its m = 0 rows (the lift of the physical perturbation
        # onto the torus' Fourier basis: any lift with the same sum over m is exact)
        self.m_zero = np.all(labels[:, 1:] == 0, axis=1) if labels.shape[1] > 1 \
            else np.ones(self.n, bool)
        p = labels[:, 0]
        self.field = np.where(np.arange(self.n) < nx, 0, 1)  # 0 theta, 1 U
        # signed bins b = j + p m0 of every (family, row), and their rfft indices
        self.b = self.j[:, None] + p[None, :] * m0  # (nf, n)
        # family m0 holds its own conjugate (bin (p + 1) m0 <-> label -p - 2)
        self.conj = self.j != m0
        self.rate = float(max(self.lam.real.max(), 0.0))
        self._own()

    def _own(self):
        """Which row deposits each lattice bin. On a ring of N sites the Fourier bins
        j + p m0 of different families can coincide mod N (aliasing: p k wraps past
        2 pi); each bin r is owned by one (family, row) - the one of smallest |p|, its
        direct bin before a conjugate one - which alone deposits its value (every row
        carries its bin's data: ``initial``)."""
        nf, n = self.b.shape
        direct = np.zeros((nf, n), bool)
        conj = np.zeros((nf, n), bool)
        owned = [set(), set()]
        order = np.argsort(np.abs(self.labels[:, 0]), kind="stable")
        for row in order:
            if not self.m_zero[row]:
                continue
            f = self.field[row]
            for i in range(nf):
                r = int(self.b[i, row] % self.N)
                if r not in owned[f]:
                    owned[f].add(r)
                    direct[i, row] = True
            for i in np.flatnonzero(self.conj):
                r = int(-self.b[i, row] % self.N)
                if r not in owned[f]:
                    owned[f].add(r)
                    conj[i, row] = True
        self.direct, self.conj_owner, self.covered = direct, conj, owned

    def initial(self, delta):
        """Family data (nf, 2n, draws) from delta = (theta, theta_dot, U, U_dot) FFTs
        (each (draws, N), normalised 1/N). Every m = 0 row gets the data of its bin, owner
        or not: a row a bin is aliased to still couples to its family's other rows (only
        the owner deposits the bin's value)."""
        nf, n = self.b.shape
        X0 = np.zeros((nf, 2 * n, delta[0].shape[0]), complex)
        r = np.mod(self.b, self.N)
        for row in np.flatnonzero(self.m_zero):
            f = self.field[row]
            X0[:, row] = delta[2 * f][:, r[:, row]].T
            X0[:, n + row] = delta[2 * f + 1][:, r[:, row]].T
        return X0

    def evolve(self, X0, t, families=slice(None)):
        """Complex amplitudes e^{i b n} of every (family, row) at times t: (nt, nf, n, draws)
        before the sum over m (rows of one p at the same bin add in the lab frame); only
        the ``families`` (a slice of them, X0 their data) when given."""
        V, lam = self.V[families], self.lam[families]
        coef = np.linalg.solve(V, X0)  # biorthogonal projection on the modes
        n, nf, draws = self.n, X0.shape[0], X0.shape[2]
        # W[f, m, r, d]: mode m's share of row r's value (the first n rows are values)
        W = (np.transpose(V[:, :n, :], (0, 2, 1))[..., None] * coef[:, :, None, :])
        # a growing mode's factor beyond e^600 is far past saturation (linear is False
        # there anyway): capped so that long runs give huge, finite factors, never inf/NaN
        grow = np.exp(np.minimum(lam.real[:, None, :] * t[None, :, None], MAX_EXPONENT))
        turns = uniform_phases(t, lam.imag.ravel()).reshape(t.size, nf, 2 * n)
        grow = grow * np.transpose(turns, (1, 0, 2))  # (nf, nt, 2n)
        out = np.matmul(grow, W.reshape(nf, 2 * n, n * draws)).reshape(nf, t.size, n, draws)
        lab = uniform_phases(t, -self.freq)  # (nt, n)
        return np.transpose(out, (1, 0, 2, 3)) * lab[:, None, :, None]


__all__ = ["Families", "MAX_EXPONENT"]
