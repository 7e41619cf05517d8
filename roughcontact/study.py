"""The multiscale fingerpad study: d_eq(F_N, U) and A_R(F_N, U) bottom-up from a scene (``docs/equivalent_gap.md``).

For each normal force F_N and voltage U:

1. **Apparent scale** (:func:`apparent_contact`): the apparent area A0 and the nominal pressures over it — one
   uniform pressure F_N/A0 for the power law of seed Eq. 27, or the Hertz pressure averaged over ``rings`` rings
   of equal area for a fingertip cap.
2. **Ridge and roughness scales** (:func:`patch_surface`, :func:`patch_body`): a periodic patch of ``periods``
   ridge periods with the ridges and the self-affine micro-roughness resolved in one grid, pressed at each
   nominal pressure with the electrostatic attraction acting (``roughcontact.solve_contact``; 0 V is the hard
   wall). Each solve starts from the result at the previous load and the same voltage, else from the previous
   voltage at the same load (``x0=``); a scene without roughness is solved for one realisation only (the
   others would be identical).
3. **Averages over the apparent area** (rings of equal area weigh equally): d_eq by seed Eq. 25
   (``DielectricStack.equivalent_gap`` of all gaps), the arithmetic mean gap, the real contact fraction, the
   ridge contact fraction A_R/A0 (:func:`ridge_area_fraction`: the real contact closed morphologically with a
   disc of diameter ℓ, at ℓ and at the scene's sensitivity factors on it), the mean attraction σ̄_el and the
   ridge-area equivalent gap d_eq,R with σ_el(d_eq,R) A_R = σ̄_el A0 (the gap that the seed's friction law,
   which applies σ_el on A_R, needs).
4. **Realisations**: ``realisations`` rough patches (rng seed + r); every reported number is a mean with a 95 %
   Student-t confidence interval (:func:`confidence_interval`) over the realisations whose solves converged (a
   solve that fails from its warm start is repeated from the solver's own start first).

Per-point results are stored as they finish in a :class:`PointStore` directory, so an interrupted run resumes
without recomputing finished points; a different scene in the same directory is refused (:class:`SceneMismatch`).
"""
from __future__ import annotations

import dataclasses
import json
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .scene import Scene

#: Two-sided confidence level of every reported interval.
CONFIDENCE = 0.95


# ---------------------------------------------------------------------------------------------------------
# Scales
# ---------------------------------------------------------------------------------------------------------
def apparent_contact(fingerpad, normal_force: float, rings: int) -> tuple:
    """``(A0 [m²], nominal pressures [Pa])`` at ``normal_force`` [N]: one pressure F_N/A0 for the power law,
    ``rings`` Hertz ring means (rings of equal area, a³ = 3 F R/(4 E*), p0 = 3F/(2π a²)) for a fingertip."""
    if fingerpad.model == "power_law":
        area = fingerpad.area_prefactor * normal_force ** fingerpad.area_exponent
        return area, (normal_force / area,)
    radius = (3 * normal_force * fingerpad.radius / (4 * fingerpad.E_star)) ** (1 / 3)
    area = np.pi * radius ** 2
    peak = 3 * normal_force / (2 * area)
    s = np.linspace(0.0, 1.0, rings + 1)                         # (r/a)² at the ring boundaries
    means = peak * (2 / 3) * ((1 - s[:-1]) ** 1.5 - (1 - s[1:]) ** 1.5) / np.diff(s)
    return area, tuple(float(p) for p in means)


def patch_grid(scene: Scene):
    """The periodic patch grid: ``grid`` × ``grid`` pixels over ``periods`` ridge periods per side."""
    from surfaces import Grid
    side = scene.preset.periods * scene.ridges.period
    return Grid((scene.preset.grid,) * 2, (side, side), periodic=True)


def resolved_short_cutoff(scene: Scene) -> float:
    """The micro-roughness short cut-off in use [m]: the scene's, raised to ``pixels_per_cutoff`` pixels."""
    spacing = patch_grid(scene).spacing[0]
    cutoff = max(scene.roughness.short_cutoff, scene.preset.pixels_per_cutoff * spacing)
    if scene.roughness.enabled and cutoff >= scene.roughness.long_cutoff:
        raise ValueError(f"roughness.long_cutoff = {scene.roughness.long_cutoff!r} m is not above the shortest "
                         f"wavelength the preset resolves, {cutoff:g} m (presets.{scene.study.preset}.grid = "
                         f"{scene.preset.grid} px, pixels_per_cutoff = {scene.preset.pixels_per_cutoff:g}); "
                         "raise the grid or the long cut-off")
    return cutoff


def ridge_heights(scene: Scene, grid=None) -> np.ndarray:
    """Heights [m] of the parallel ridges on ``grid`` (default: the patch grid); zero when disabled."""
    from surfaces import parallel_ridges
    grid = patch_grid(scene) if grid is None else grid
    if not scene.ridges.enabled:
        return np.zeros(grid.shape)
    return parallel_ridges(grid, period=scene.ridges.period, height=scene.ridges.height,
                           ridge_width_ratio=scene.ridges.width_ratio).heights


def roughness_heights(scene: Scene, realisation: int) -> np.ndarray:
    """Heights [m] of the micro-roughness of ``realisation`` on the patch grid (rng seed + realisation); zero
    when disabled."""
    from surfaces import self_affine
    grid = patch_grid(scene)
    if not scene.roughness.enabled:
        return np.zeros(grid.shape)
    if scene.roughness.long_cutoff > grid.lengths[0]:
        raise ValueError(f"roughness.long_cutoff = {scene.roughness.long_cutoff!r} m exceeds the patch side "
                         f"{grid.lengths[0]:g} m (presets.{scene.study.preset}.periods x ridges.period); "
                         "valid range (short_cutoff, patch side]")
    return self_affine(grid, scene.roughness.hurst, rms_height=scene.roughness.rms_height,
                       long_cutoff=scene.roughness.long_cutoff, short_cutoff=resolved_short_cutoff(scene),
                       rng=scene.study.seed + realisation).heights


def patch_surface(scene: Scene, realisation: int) -> np.ndarray:
    """Heights [m] of the patch of ``realisation``: ridges plus micro-roughness."""
    heights = ridge_heights(scene) + roughness_heights(scene, realisation)
    if not heights.any():
        raise ValueError("the patch is flat: enable ridges (ridges.enabled, ridges.height > 0) or roughness "
                         "(roughness.enabled)")
    return heights


def patch_body(scene: Scene, grid=None):
    """The skin under the patch on ``grid`` (default: the patch grid): a half-space of ``skin.E_star``, or the
    layer bonded on it."""
    from .elastic import ElasticHalfSpace
    skin = scene.skin
    grid = patch_grid(scene) if grid is None else grid
    if skin.layer_thickness == 0:
        return ElasticHalfSpace(grid, E_star=skin.E_star)
    return ElasticHalfSpace(grid, E_star=skin.layer_E_star, thickness=skin.layer_thickness,
                            poisson=skin.poisson, substrate_E_star=skin.E_star, substrate_poisson=skin.poisson)


def realisation_count(scene: Scene) -> int:
    """Distinct patches: the preset's realisations, one when nothing in the patch is random."""
    return scene.preset.realisations if scene.roughness.enabled else 1


def ridge_area_fraction(contact: np.ndarray, spacing: float, length: float) -> float:
    """A_R/A0 of a periodic contact mask: the fraction covered after a morphological closing (dilation, then
    erosion) with a disc of diameter ``length`` [m] on pixels of ``spacing`` [m]; micro-contacts closer than
    ``length`` merge into one ridge contact. A disc under one pixel radius leaves the mask as it is. Periodic
    convolutions by FFT (counts rounded), so the cost does not grow with the disc."""
    import scipy.fft
    contact = np.asarray(contact, dtype=float)
    radius = 0.5 * length / spacing
    if radius < 1:
        return float(np.mean(contact))
    rows, columns = (np.fft.fftfreq(n, 1 / n) for n in contact.shape)     # signed pixel offsets, wrapped
    disc = (rows[:, None] ** 2 + columns[None, :] ** 2 <= radius ** 2).astype(float)
    kernel = scipy.fft.rfft2(disc)

    def covered(mask):
        return scipy.fft.irfft2(scipy.fft.rfft2(mask) * kernel, s=contact.shape)

    dilated = (covered(contact) > 0.5).astype(float)
    return float(np.mean(covered(dilated) > disc.sum() - 0.5))


def confidence_interval(samples) -> tuple:
    """``(mean, half-width)`` of the two-sided :data:`CONFIDENCE` Student-t interval over the last axis; NaN
    samples are left out (half-width NaN where fewer than two remain, mean NaN where none)."""
    from scipy.special import stdtrit
    samples = np.asarray(samples, dtype=float)
    count = np.sum(np.isfinite(samples), axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.nansum(samples, axis=-1) / count
        spread = np.sqrt(np.nansum((samples - mean[..., None]) ** 2, axis=-1) / (count - 1))
        half = np.where(count > 1, stdtrit(np.maximum(count - 1, 1), 0.5 + CONFIDENCE / 2) * spread
                        / np.sqrt(count), np.nan)
    return mean, half


# ---------------------------------------------------------------------------------------------------------
# One (F_N, U) point
# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PointResult:
    """The study at one (F_N [N], U [V]); tuples run over the realisations (``ridge_area_fractions`` over the
    coarse-graining lengths first). SI units: areas m², gaps m, pressures Pa; ``seconds`` of solving."""

    normal_force: float
    voltage: float
    apparent_area: float
    nominal_pressures: tuple
    equivalent_gap: tuple
    ridge_equivalent_gap: tuple
    mean_gap: tuple
    contact_fraction: tuple
    ridge_area_fractions: tuple
    electrostatic_pressure: tuple
    gap_slope: tuple
    converged: tuple
    iterations: tuple
    seconds: float

    def to_json(self) -> str:
        return json.dumps(dataclasses.asdict(self))

    @classmethod
    def from_json(cls, text: str) -> PointResult:
        data = json.loads(text)
        return cls(**{key: _tuples(value) for key, value in data.items()})


def _tuples(value):
    return tuple(_tuples(v) for v in value) if isinstance(value, list) else value


def _gap_slope(gap, weights, spacing) -> float:
    """rms gap slope |∇g| weighted by ``weights`` (periodic central differences)."""
    gx = (np.roll(gap, -1, 0) - np.roll(gap, 1, 0)) / (2 * spacing[0])
    gy = (np.roll(gap, -1, 1) - np.roll(gap, 1, 1)) / (2 * spacing[1])
    return float(np.sqrt(np.sum(weights * (gx ** 2 + gy ** 2)) / np.sum(weights)))


def _point_result(stack, force, voltage, area, pressures, solved, lengths, spacing, seconds):
    """Average the solved patches (``solved[r][k]``: realisation r, ring k) over the apparent area."""
    columns = {name: [] for name in ("equivalent_gap", "ridge_equivalent_gap", "mean_gap", "contact_fraction",
                                     "electrostatic_pressure", "gap_slope", "converged", "iterations")}
    ridge = [[] for _ in lengths]
    offset = stack.eps_a * stack.dielectric_offset
    for results in solved:
        gaps = np.stack([np.asarray(res.gap) for res in results])
        d_eq = stack.equivalent_gap(gaps)
        fractions = [float(np.mean([ridge_area_fraction(np.asarray(res.contact), spacing[0], length)
                                    for res in results])) for length in lengths]
        for column, fraction in zip(ridge, fractions):
            column.append(fraction)
        # σ_el(d_eq,R) A_R = σ_el(d_eq) A0: (c + d_R/ε_a)² = (A_R/A0) (c + d_eq/ε_a)²
        d_ridge = stack.eps_a * (np.sqrt(fractions[0]) * stack.electrical_thickness(d_eq) - stack.dielectric_offset)
        columns["equivalent_gap"].append(d_eq)
        columns["ridge_equivalent_gap"].append(max(float(d_ridge), 0.0))
        columns["mean_gap"].append(float(gaps.mean()))
        columns["contact_fraction"].append(float(np.mean([res.contact_fraction for res in results])))
        columns["electrostatic_pressure"].append(float(np.mean(stack.pressure(gaps, voltage))))
        columns["gap_slope"].append(float(np.mean([_gap_slope(g, (offset + g) ** -2.0, spacing) for g in gaps])))
        columns["converged"].append(all(bool(res.converged) for res in results))
        columns["iterations"].append(int(sum(res.iterations for res in results)))
    return PointResult(normal_force=force, voltage=voltage, apparent_area=float(area),
                       nominal_pressures=tuple(pressures), ridge_area_fractions=tuple(map(tuple, ridge)),
                       seconds=seconds, **{name: tuple(values) for name, values in columns.items()})


# ---------------------------------------------------------------------------------------------------------
# Storage and resume
# ---------------------------------------------------------------------------------------------------------
class SceneMismatch(ValueError):
    """A results directory that holds another scene's results."""


class DirectoryInUse(ValueError):
    """A results directory that another running study is writing into."""


class PointStore:
    """Per-point results in ``directory/points/`` beside ``directory/scene.toml``; refuses another scene, and a
    directory that a running process holds (``run.lock`` with its process id; a lock of a process that no
    longer runs, e.g. one that was killed, is taken over). :meth:`release` frees the directory."""

    def __init__(self, directory, scene: Scene):
        from .scene import load_scene
        self.directory = Path(directory)
        self.points = self.directory / "points"
        stored = self.directory / "scene.toml"
        if stored.exists():
            old = load_scene(stored)
            if old != scene:
                new, before = scene.flat(), old.flat()
                changed = [f"{key} = {before[key]!r} -> {new[key]!r}" for key in new if new[key] != before.get(key)]
                raise SceneMismatch(f"{self.directory} holds the results of another scene ({'; '.join(changed)}); "
                                    "run into a new --out directory, or delete this one to start over")
        else:
            self.directory.mkdir(exist_ok=True)
            _write_atomic(stored, scene.to_toml())
        self.points.mkdir(exist_ok=True)
        self.lock = self.directory / "run.lock"
        try:
            descriptor = os.open(self.lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY)     # atomic: one run wins
        except FileExistsError:
            try:
                holder = int(self.lock.read_text())
            except (OSError, ValueError):
                holder = None
            if holder is not None and holder != os.getpid() and _running(holder):
                raise DirectoryInUse(f"{self.directory} is being written by another roughcontact run (process "
                                     f"{holder}); wait for it to finish or choose another --out directory") from None
            _write_atomic(self.lock, str(os.getpid()))                                # a stale lock: taken over
        else:
            with os.fdopen(descriptor, "w") as stream:
                stream.write(str(os.getpid()))

    def release(self) -> None:
        """Free the directory for other runs."""
        self.lock.unlink(missing_ok=True)

    def _path(self, i: int, j: int) -> Path:
        return self.points / f"F{i:03d}_U{j:03d}.json"

    def load(self, i: int, j: int) -> PointResult | None:
        path = self._path(i, j)
        return PointResult.from_json(path.read_text()) if path.exists() else None

    def save(self, i: int, j: int, point: PointResult) -> None:
        _write_atomic(self._path(i, j), point.to_json())


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:                     # it runs, under another user
        return True
    return True


def _write_atomic(path: Path, text: str) -> None:
    temporary = path.with_name(path.name + ".part")
    temporary.write_text(text)
    os.replace(temporary, path)


# ---------------------------------------------------------------------------------------------------------
# The sweep
# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StudyResult:
    """All points of a study; ``points[i][j]`` at ``normal_forces[i]``, ``voltages[j]``; ``coarse_graining``
    the A_R closing diameters [m] (the scene's first); ``computed`` points solved in this run and ``solves``
    the contact solves they took; ``short_cutoff`` the micro-roughness cut-off in use [m]."""

    scene: Scene
    points: tuple
    coarse_graining: tuple
    short_cutoff: float
    computed: int
    solves: int

    @property
    def normal_forces(self) -> np.ndarray:
        return np.array(self.scene.loads.normal_forces)

    @property
    def voltages(self) -> np.ndarray:
        return np.array(self.scene.loads.voltages)

    def array(self, name: str) -> np.ndarray:
        """Field ``name`` of every point: shape (loads, voltages, realisations), or (…, lengths, realisations)
        for ``ridge_area_fractions``, or (loads, voltages) for scalars."""
        return np.array([[getattr(point, name) for point in row] for row in self.points], dtype=float)

    def summary(self, name: str) -> tuple:
        """``(mean, 95 % half-width)`` of field ``name`` over the realisations whose solves converged."""
        values, converged = self.array(name), self.array("converged").astype(bool)
        if converged.ndim < values.ndim:                       # ridge_area_fractions: (…, lengths, realisations)
            converged = converged[:, :, None, :]
        return confidence_interval(np.where(converged, values, np.nan))

    @property
    def ridge_area(self) -> np.ndarray:
        """A_R/A0 at the scene's coarse-graining length, shape (loads, voltages, realisations)."""
        return self.array("ridge_area_fractions")[:, :, 0, :]


def _lengths(scene: Scene) -> tuple:
    length = scene.ridge_area.coarse_graining
    return (length, *(factor * length for factor in scene.ridge_area.sensitivity))


def run_study(scene: Scene, directory=None, progress: bool = False) -> StudyResult:
    """Run (or resume, with a ``directory``) the study of ``scene``; ``progress`` shows a tqdm bar."""
    from .contact import solve_contact
    from .interactions import ElectrostaticInteraction

    store = None if directory is None else PointStore(directory, scene)
    stack = scene.screen.stack()
    grid = patch_grid(scene)
    lengths = _lengths(scene)
    cutoff = resolved_short_cutoff(scene) if scene.roughness.enabled else float("nan")
    forces, voltages = scene.loads.normal_forces, scene.loads.voltages
    rings = scene.preset.rings if scene.fingerpad.model == "fingertip" else 1
    count = realisation_count(scene)
    order = [(i, j) for i in range(len(forces)) for j in range(len(voltages))]
    points = {}
    if store is not None:
        points = {(i, j): point for i, j in order if (point := store.load(i, j)) is not None}
    todo = [key for key in order if key not in points]
    heights, body = {}, None
    along_load = {}       # (realisation, ring, voltage) -> the result at the previous load
    along_voltage = {}    # (realisation, ring, load index) -> the result at the previous voltage of that load
    solves = 0
    bar = None
    if progress and todo:
        from tqdm import tqdm
        bar = tqdm(total=len(todo), desc="roughcontact run", unit="point")
    try:
        for i, j in todo:
            force, voltage = forces[i], voltages[j]
            area, pressures = apparent_contact(scene.fingerpad, force, rings)
            start = time.perf_counter()
            if body is None:
                body = patch_body(scene)
            law = ElectrostaticInteraction(stack, voltage=voltage) if voltage > 0 else None   # 0 V: the hard wall
            solved = []
            for r in range(count):
                if r not in heights:
                    heights[r] = patch_surface(scene, r)
                results = []
                for k, pressure in enumerate(pressures):
                    x0 = along_load.get((r, k, voltage)) or along_voltage.get((r, k, i))
                    result = solve_contact(heights[r], body, mean_pressure=pressure, interaction=law,
                                           tol=scene.preset.tolerance, x0=x0, warn=False)
                    solves += 1
                    if not result.converged and x0 is not None:    # a failed warm start: the solver's own start
                        result = solve_contact(heights[r], body, mean_pressure=pressure, interaction=law,
                                               tol=scene.preset.tolerance, warn=False)
                        solves += 1
                    along_load[(r, k, voltage)] = along_voltage[(r, k, i)] = result
                    results.append(result)
                solved.append(results)
            point = _point_result(stack, force, voltage, area, pressures, solved, lengths, grid.spacing,
                                  time.perf_counter() - start)
            points[(i, j)] = point
            for key in [key for key in along_voltage if key[2] < i]:      # earlier loads are not revisited
                del along_voltage[key]
            if store is not None:
                store.save(i, j, point)
            if bar is not None:
                bar.update()
    finally:
        if bar is not None:
            bar.close()
        if store is not None:
            store.release()
    table = tuple(tuple(points[(i, j)] for j in range(len(voltages))) for i in range(len(forces)))
    return StudyResult(scene=scene, points=table, coarse_graining=lengths, short_cutoff=cutoff,
                       computed=len(todo), solves=solves)
