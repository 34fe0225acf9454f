"""Probe 100: a model map whose semi-discrete NLS and exact verdicts differ says so, and
why, in a line of its own (before, a map of a three-field hinge chain printed NLS 47% MI
and exact 93% with nothing said about the cells between them: its rotational carrier
decays by a three-wave process the NLS cannot see)."""

from __future__ import annotations

import math
import re

from cli.app import main

# rigid units (half-length 1) with rotation theta, axial U and transverse V, joined by
# hinges with an axial spring 1, a shear spring K_s and a bending spring K_b
HINGE3 = '''name = "hinge3"
fields = ["theta", "U", "V"]
branch = "theta"
[parameters]
J = 0.5
K_s = 0.1
K_b = 0.05
[energy]
kinetic = "J*theta_t**2/2 + U_t**2/2 + V_t**2/2"
bond = "(U_next - U + 2 - cos(theta) - cos(theta_next))**2/2 + K_s*(V_next - V - sin(theta) - sin(theta_next))**2/2 + K_b*(theta_next - theta)**2/2"
'''


def hand_omegas(k, J=0.5, K_s=0.1, K_b=0.05):
    """The three branches by hand, ascending: U decouples (2 |sin k/2|); theta and V obey
    J w^4 - 4 w^2 (K_s c^2 + K_b s^2 + J K_s s^2) + 16 K_s K_b s^4 = 0."""
    s, c = math.sin(k / 2), math.cos(k / 2)
    b = 4 * (K_s * c * c + K_b * s * s + J * K_s * s * s)
    d = math.sqrt(b * b - 64 * J * K_s * K_b * s ** 4)
    return sorted([math.sqrt((b - d) / (2 * J)), math.sqrt((b + d) / (2 * J)), 2 * abs(s)])


def test_a_map_says_where_and_why_the_nls_and_the_exact_theory_differ(tmp_path, capsys):
    f = tmp_path / "hinge3.toml"
    f.write_text(HINGE3)
    assert main(["map", "--model", str(f), "--param", "K_s=0.1:0.1:1", "--k", "0.3,1.6",
                 "--amplitude", "0.1", "--N", "128", "--theory-only", "--exact",
                 "--workers", "1", "--out", str(tmp_path / "m")]) == 0
    out = capsys.readouterr().out
    line = next((ln for ln in out.splitlines() if "differ in" in ln), None)
    assert line is not None, out
    assert "differ in 1 of 2 cells" in line and "NLS stable, exact MI" in line
    m = re.search(r"three-wave decay of the carrier into branch (\d) at (-?[\d.]+) and "
                  r"branch (\d) at (-?[\d.]+) grows at about ([\d.e-]+)", line)
    assert m, line
    # the decay it names is a resonance of this chain's own branches, by hand: wavenumbers
    # summing to the carrier's, frequencies to its (the carrier the theta-dominated upper
    # theta-V root at k = 1.6 snapped to 2 pi 33 / 128, below U's here); detuned by at most a few growth rates (a
    # three-wave band is as wide as its rate), here within 3x of it
    k = 2 * math.pi * 33 / 128
    b1, k1, b2, k2, rate = int(m[1]), float(m[2]), int(m[3]), float(m[4]), float(m[5])
    assert abs(math.remainder(k1 + k2 - k, 2 * math.pi)) < 1e-3
    w = max(x for x in hand_omegas(k) if abs(x - 2 * math.sin(k / 2)) > 1e-9)
    detune = abs(hand_omegas(k1)[b1] + hand_omegas(k2)[b2] - w)
    assert detune < 3 * rate, (detune, rate)
    # and the point it names, run as printed, explains the same cell in its notes
    cmd = re.search(r"`flexmm (point [^`]+)`", line)[1].split()
    assert main([*cmd, "--json"]) == 0
    import json

    notes = " ".join(json.loads(capsys.readouterr().out)["notes"])
    assert "three-wave decay" in notes


def _hand_theta_index(k, J=0.5, K_s=0.1, K_b=0.05):
    """The index (ascending) of the root whose kinetic energy theta carries most of, by
    hand: the theta-V block K = [[4 K_s s^2, 2 i K_s sin k], [-2 i K_s sin k, 4 K_s c^2 +
    4 K_b s^2]] (V, theta) with masses (1, J); U (2 |sin k/2|) is pure U."""
    import numpy as np

    s, c = math.sin(k / 2), math.cos(k / 2)
    K = np.array([[4 * K_s * s * s, 2j * K_s * math.sin(k)],
                  [-2j * K_s * math.sin(k), 4 * K_s * c * c + 4 * K_b * s * s]])
    Mh = np.diag([1.0, 1 / math.sqrt(J)])  # M^(-1/2)
    w2, v = np.linalg.eigh(Mh @ K @ Mh)
    theta = max(range(2), key=lambda i: abs(v[1, i]) ** 2)  # kinetic share of theta
    w = math.sqrt(w2[theta])
    return min(range(3), key=lambda i: abs(hand_omegas(k, J, K_s, K_b)[i] - w))


def test_a_map_says_where_the_named_branch_changes_index(tmp_path, capsys):
    f = tmp_path / "hinge3.toml"
    f.write_text(HINGE3)
    ks = (0.2, 1.0, 1.6, 2.8)
    assert main(["map", "--model", str(f), "--param", "K_s=0.1,0.2", "--k",
                 ",".join(map(str, ks)), "--amplitude", "0.1", "--theory-only",
                 "--workers", "1", "--out", str(tmp_path / "m")]) == 0
    out = capsys.readouterr().out
    line = next((ln for ln in out.splitlines() if "changes along k" in ln), None)
    assert line is not None, out
    # each row's own indices (newuser 101: the note gave the file's K_s's for every row;
    # at K_s 0.2 the theta carrier goes 2, 1, 0 where at 0.1 it goes 2, 1)
    for ks_row in (0.1, 0.2):
        part = re.search(rf"at K_s = {ks_row:g}: (.*?)(; at K_s|; each k)", line)
        assert part is not None, line
        got = [int(x) for x in re.findall(r"index (\d) at k", part[1])]
        want = []
        for k in ks:  # the runs of equal indices, by hand
            b = _hand_theta_index(k, K_s=ks_row)
            if not want or want[-1] != b:
                want.append(b)
        assert got == want and len(want) >= 2, (line, ks_row, want)
