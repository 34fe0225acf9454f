"""The scene registry and the checks a scene reports.

A scene registers itself with :func:`register`; ``flexmm scenes`` lists the registry and
the tests run every registered scene. A check says what it compares and what is expected:
agreement, or a known disagreement with the paper (an erratum or a finding in docs/), so
the report calls "FAIL" only what nobody expected.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

#: expectation of a check: theory and numerics agree
AGREE = "agree"


@dataclass(frozen=True)
class Scene:
    """One figure: ``compute(ctx) -> (data, summary)``, ``plot(data) -> Figure``.

    ``data`` holds everything ``plot`` needs (arrays and plain values); it is stored in
    ``data.h5``, so ``plot`` can redraw the figure without computing. ``summary`` holds
    the ``checks`` and any numbers the report shows; ``report(summaries)`` (optional)
    returns the scene's own Markdown section of ``report.md``.
    """

    name: str
    description: str
    figure: str  # the paper's figure it reproduces, or "beyond the paper"
    runtime: str  # expected run time, full (quick)
    simulates: bool
    compute: Callable = field(repr=False)
    plot: Callable = field(repr=False)
    report: Callable | None = field(default=None, repr=False)


#: the scene modules, in registration order: imported on the registry's first use, so that
#: `flexmm --help` and `flexmm coefficients` import no figure module (nor matplotlib)
SCENE_MODULES = ("fig2_dispersion", "fig3_g_sign", "fig3_simulated", "fig4_km_map",
                 "fig5_8_plane_waves", "fig9_mi_band", "gain_spectrum", "gain_theories",
                 "harmonics", "solitons", "four_wave_pairs")
#: the names they register (for `flexmm scene NAME --help` without importing them; a test
#: checks it against the registry)
SCENE_NAMES = ("fig2-dispersion", "fig3-g-sign", "fig3-simulated", "fig4-km-map",
               "fig5-blue-rotation", "fig6-blue-coupled", "fig7-green-rotation",
               "fig8-green-coupled", "fig9-mi-band", "gain-spectrum", "gain-theories",
               "harmonics", "soliton-bright", "soliton-dark", "soliton-convergence",
               "soliton-existence", "four-wave-pairs")


class _Registry(dict):
    """The scenes by name; reading it first imports every scene module (they register)."""

    _loaded = False

    def _load(self):
        if not _Registry._loaded:
            _Registry._loaded = True  # first: the modules' register() reads the registry
            import importlib

            for module in SCENE_MODULES:
                importlib.import_module(f"{__package__}.{module}")

    def __getitem__(self, key):
        self._load()
        return super().__getitem__(key)

    def __contains__(self, key):
        self._load()
        return super().__contains__(key)

    def __iter__(self):
        self._load()
        return super().__iter__()

    def __len__(self):
        self._load()
        return super().__len__()

    def get(self, key, default=None):
        self._load()
        return super().get(key, default)

    def keys(self):
        self._load()
        return super().keys()

    def values(self):
        self._load()
        return super().values()

    def items(self):
        self._load()
        return super().items()


REGISTRY: dict[str, Scene] = _Registry()


def register(scene: Scene) -> Scene:
    if scene.name in REGISTRY:
        raise ValueError(f"scene {scene.name!r} registered twice")
    REGISTRY[scene.name] = scene
    return scene


def get_scene(name: str) -> Scene:
    if name not in REGISTRY:
        raise ValueError(f"unknown scene {name!r}; `flexmm scenes` lists: "
                         f"{', '.join(REGISTRY)}")
    return REGISTRY[name]


def known(reason: str) -> str:
    """Expectation of a check that records a known disagreement with the paper;
    ``reason`` names it: "erratum 6" or "finding: <what>, <docs page and section>"."""
    return f"paper disagrees ({reason})"


def check(name: str, theory: str, numerics: str, agrees: bool, expect: str = AGREE) -> dict:
    """One row of the report: what is compared, the two sides, whether they agree, and
    whether agreement was expected (``AGREE``) or a known disagreement (:func:`known`)."""
    agrees = bool(agrees)
    expected = (expect == AGREE) == agrees
    if expected:
        outcome = "agrees" if agrees else expect
    else:
        outcome = "FAIL" if expect == AGREE else "FAIL (expected: " + expect + ")"
    return {"check": name, "theory": theory, "numerics": numerics, "agrees": agrees,
            "expect": expect, "outcome": outcome, "pass": expected}
