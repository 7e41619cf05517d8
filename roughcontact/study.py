"""The multiscale fingerpad study: d_eq(F_N, U) and A_R(F_N, U) bottom-up from a scene (``docs/equivalent_gap.md``).

For each normal force F_N and voltage U:

1. **Apparent scale** (:func:`apparent_contact`): the apparent area A0 and the nominal pressures over it — one
   uniform pressure F_N/A0 for the power law of seed Eq. 27, or the Hertz pressure averaged over ``rings`` rings
   of equal area for a fingertip cap.
2. **Ridge and roughness scales** (:func:`patch_surface`, :func:`patch_body`): a periodic patch of ``periods``
   ridge periods with the ridges and the self-affine micro-roughness resolved in one grid, pressed at each
   nominal pressure with the electrostatic attraction acting (``roughcontact.solve_contact``; 0 V is the hard
   wall). A scene without roughness is solved for one realisation only (the others would be identical).
3. **Averages over the apparent area** (rings of equal area weigh equally): d_eq by seed Eq. 25
   (``DielectricStack.equivalent_gap`` of all gaps), the arithmetic mean gap, the real contact fraction, the
   ridge contact fraction A_R/A0 (:func:`ridge_area_fraction`: the real contact closed morphologically with a
   disc of diameter ℓ, at ℓ and at the scene's sensitivity factors on it), the mean attraction σ̄_el and the
   ridge-area equivalent gap d_eq,R with σ_el(d_eq,R) A_R = σ̄_el A0 (the gap that the seed's friction law,
   which applies σ_el on A_R, needs).
4. **Realisations**: ``realisations`` rough patches (rng seed + r); every reported number is a mean with a 95 %
   Student-t confidence interval (:func:`confidence_interval`) over the realisations whose solves converged (a
   solve that fails from its warm start is repeated from the solver's own start first).

**Tasks.** The sweep is split into independent, deterministic tasks, one per (realisation r, voltage index j)
(:func:`solve_chain`): every load in order, each solve warm-started from the previous load's result (``x0=``;
cold solves with the preset's ``warm_start`` false). A task takes the scene, r, j and its FFT thread count and
returns one :class:`PatchRecord` per load; nothing passes between tasks, so a point's numbers do not depend on
where its tasks ran or in which order they finished. :func:`run_study` runs them in this process, in a local
process pool or on a dask.distributed cluster through one loop (submit, consume as completed, store), and
assembles the :class:`PointResult` of each (F_N, U) from the records of its realisations.

Finished tasks are stored as they arrive in a :class:`TaskStore` directory, so an interrupted run resumes
without recomputing finished tasks; a different scene in the same directory is refused (:class:`SceneMismatch`).
"""
from __future__ import annotations

import dataclasses
import json
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .provenance import write_atomic
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


def apparent_scale(scene: Scene) -> tuple:
    """``(A0 [m²], nominal pressures [Pa])`` at each of the scene's normal forces: :func:`apparent_contact`, or
    for a fingertip with ``fingerpad.layer`` the cap solved on the skin's layer over the tissue
    (:func:`roughcontact.fingertip.fingertip_contact` on ``fingerpad.layer_grid``² pixels; ``ValueError`` where a
    solve does not converge)."""
    rings, fingerpad = _rings(scene), scene.fingerpad
    if fingerpad.model != "fingertip" or not fingerpad.layer:
        return tuple(apparent_contact(fingerpad, force, rings) for force in scene.loads.normal_forces)
    from .fingertip import fingertip_contact
    scales = []
    for force in scene.loads.normal_forces:
        contact = fingertip_contact(fingerpad, scene.skin, force, rings, grid_points=fingerpad.layer_grid)
        if not contact.converged:
            raise ValueError(f"the fingertip on the layered skin did not converge at loads.normal_forces = {force!r} "
                             f"N ({contact.iterations} iterations on fingerpad.layer_grid = {fingerpad.layer_grid} "
                             "px); refine layer_grid or set fingerpad.layer = false")
        scales.append((contact.area, contact.pressures))
    return tuple(scales)


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


def ridge_heights(scene: Scene, grid=None, realisation: int = 0) -> np.ndarray:
    """Heights [m] of the parallel ridges on ``grid`` (default: the patch grid), with the sweat pores of
    ``realisation`` (rng stream (seed + realisation, 1), apart from the roughness's); zero when disabled."""
    from surfaces import parallel_ridges
    grid = patch_grid(scene) if grid is None else grid
    ridges = scene.ridges
    if not ridges.enabled:
        return np.zeros(grid.shape)
    return parallel_ridges(grid, period=ridges.period, height=ridges.height, ridge_width_ratio=ridges.width_ratio,
                           pore_density=ridges.pore_density, pore_diameter=ridges.pore_diameter,
                           pore_depth=ridges.pore_depth,
                           rng=np.random.default_rng((scene.study.seed + realisation, 1))).heights


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
    heights = ridge_heights(scene, realisation=realisation) + roughness_heights(scene, realisation)
    if not heights.any():
        raise ValueError("the patch is flat: enable ridges (ridges.enabled, ridges.height > 0) or roughness "
                         "(roughness.enabled)")
    return heights


def patch_body(scene: Scene, grid=None, threads=None):
    """The skin under the patch on ``grid`` (default: the patch grid): a half-space of ``skin.E_star``, or the
    layer bonded on it; in the preset's dtype, with ``threads`` FFT threads (default: ``roughcontact.fft``'s)."""
    from .fingertip import skin_body
    grid = patch_grid(scene) if grid is None else grid
    return skin_body(grid, scene.skin, scene.skin.E_star, threads=threads, dtype=scene.preset.dtype)


def realisation_count(scene: Scene) -> int:
    """Distinct patches: the preset's realisations, one when nothing in the patch is random."""
    pores = scene.ridges.enabled and scene.ridges.pore_density > 0
    return scene.preset.realisations if scene.roughness.enabled or pores else 1


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
# One task: a realisation at one voltage, every load
# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PatchRecord:
    """One realisation's patch at one (F_N, U), averaged over the rings: ``equivalent_gap`` d_eq,
    ``ridge_equivalent_gap`` d_eq,R, ``mean_gap`` [m]; ``contact_fraction``; ``ridge_area_fractions`` A_R/A0
    per coarse-graining length; ``electrostatic_pressure`` σ̄_el [Pa]; ``gap_slope`` (rms |∇g|, weighted by
    (ε_a c + g)⁻²); ``converged`` (every ring); ``iterations``, ``unstable_steps`` (concave steps: the solves
    crossed instabilities, so the answer may depend on the path; ``docs/interactions.md``) and ``solves`` (summed
    over the rings, a cold retry included); ``seconds`` of solving."""

    equivalent_gap: float
    ridge_equivalent_gap: float
    mean_gap: float
    contact_fraction: float
    ridge_area_fractions: tuple
    electrostatic_pressure: float
    gap_slope: float
    converged: bool
    iterations: int
    unstable_steps: int
    solves: int
    seconds: float


_RECORD_FIELDS = {f.name for f in dataclasses.fields(PatchRecord)}


def _gap_slope(gap, weights, spacing) -> float:
    """rms gap slope |∇g| weighted by ``weights`` (periodic central differences)."""
    gx = (np.roll(gap, -1, 0) - np.roll(gap, 1, 0)) / (2 * spacing[0])
    gy = (np.roll(gap, -1, 1) - np.roll(gap, 1, 1)) / (2 * spacing[1])
    return float(np.sqrt(np.sum(weights * (gx ** 2 + gy ** 2)) / np.sum(weights)))


def ridge_equivalent_gap(stack, equivalent_gap: float, ridge_area_fraction: float) -> float:
    """d_eq,R [m]: the uniform gap over A_R that carries the attraction σ̄_el A0 of ``equivalent_gap`` d_eq [m]
    over A0, σ_el(d_eq,R) A_R = σ_el(d_eq) A0, i.e. (c + d_eq,R/ε_a)² = (A_R/A0)(c + d_eq/ε_a)² (seed Eq. 21);
    0 where A_R/A0 (``ridge_area_fraction``) is too small for a positive gap."""
    electrical = np.sqrt(ridge_area_fraction) * stack.electrical_thickness(equivalent_gap)
    return max(float(stack.eps_a * (electrical - stack.dielectric_offset)), 0.0)


def _patch_record(stack, voltage, results, lengths, spacing, solves, seconds) -> PatchRecord:
    """Average the solved rings ``results`` of one patch over the apparent area (gaps in float64)."""
    gaps = np.stack([np.asarray(res.gap, dtype=np.float64) for res in results])
    d_eq = stack.equivalent_gap(gaps)
    fractions = tuple(float(np.mean([ridge_area_fraction(np.asarray(res.contact), spacing[0], length)
                                     for res in results])) for length in lengths)
    offset = stack.eps_a * stack.dielectric_offset
    return PatchRecord(
        equivalent_gap=float(d_eq), ridge_equivalent_gap=ridge_equivalent_gap(stack, d_eq, fractions[0]),
        mean_gap=float(gaps.mean()),
        contact_fraction=float(np.mean([res.contact_fraction for res in results])), ridge_area_fractions=fractions,
        electrostatic_pressure=float(np.mean(stack.pressure(gaps, voltage))),
        gap_slope=float(np.mean([_gap_slope(g, (offset + g) ** -2.0, spacing) for g in gaps])),
        converged=all(bool(res.converged) for res in results), iterations=int(sum(res.iterations for res in results)),
        unstable_steps=int(sum(res.unstable_steps for res in results)), solves=solves, seconds=seconds)


def _rings(scene: Scene) -> int:
    return scene.preset.rings if scene.fingerpad.model == "fingertip" else 1


def _lengths(scene: Scene) -> tuple:
    length = scene.ridge_area.coarse_graining
    return (length, *(factor * length for factor in scene.ridge_area.sensitivity))


def solve_chain(scene: Scene, realisation: int, voltage_index: int, threads: int | None = None,
                apparent: tuple | None = None) -> tuple:
    """One task of the study: the patch of ``realisation`` at voltage ``loads.voltages[voltage_index]`` under
    every load of the scene in order, each ring's solve warm-started from its result at the previous load (cold
    with the preset's ``warm_start`` false; a warm start that fails is repeated cold). ``threads`` FFT threads
    (default: ``roughcontact.fft.default_threads``); ``apparent``, the scene's :func:`apparent_scale` (computed
    when not given). Returns one :class:`PatchRecord` per load; deterministic, so the records do not depend on
    where the task runs."""
    from .contact import solve_contact
    from .interactions import ElectrostaticInteraction

    stack = scene.screen.stack()
    voltage = scene.loads.voltages[voltage_index]
    law = ElectrostaticInteraction(stack, voltage=voltage) if voltage > 0 else None       # 0 V: the hard wall
    heights, body = patch_surface(scene, realisation), patch_body(scene, threads=threads)
    lengths, spacing = _lengths(scene), patch_grid(scene).spacing
    warm_start = scene.preset.warm_start
    latest = [None] * _rings(scene)                         # each ring's last result: the next load's x0
    records = []
    for _, pressures in apparent_scale(scene) if apparent is None else apparent:
        start, solves = time.perf_counter(), 0
        for k, pressure in enumerate(pressures):
            x0 = latest[k] if warm_start else None
            result = solve_contact(heights, body, mean_pressure=pressure, interaction=law,
                                   tol=scene.preset.tolerance, x0=x0, warn=False)
            solves += 1
            if not result.converged and x0 is not None:          # a failed warm start: the solver's own start
                result = solve_contact(heights, body, mean_pressure=pressure, interaction=law,
                                       tol=scene.preset.tolerance, warn=False)
                solves += 1
            latest[k] = result
        records.append(_patch_record(stack, voltage, latest, lengths, spacing, solves,
                                     time.perf_counter() - start))
    return tuple(records)


# ---------------------------------------------------------------------------------------------------------
# One (F_N, U) point
# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PointResult:
    """The study at one (F_N [N], U [V]); tuples run over the realisations (``ridge_area_fractions`` over the
    coarse-graining lengths first). SI units: areas m², gaps m, pressures Pa; ``seconds`` of solving, summed
    over the realisations."""

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
    unstable_steps: tuple
    seconds: float


_PER_REALISATION = ("equivalent_gap", "ridge_equivalent_gap", "mean_gap", "contact_fraction",
                    "electrostatic_pressure", "gap_slope", "converged", "iterations", "unstable_steps")


def _point_result(force, voltage, area, pressures, records) -> PointResult:
    """The point from the :class:`PatchRecord` of each realisation (in realisation order)."""
    return PointResult(normal_force=force, voltage=voltage, apparent_area=float(area),
                       nominal_pressures=tuple(pressures),
                       ridge_area_fractions=tuple(zip(*(record.ridge_area_fractions for record in records))),
                       seconds=sum(record.seconds for record in records),
                       **{name: tuple(getattr(record, name) for record in records) for name in _PER_REALISATION})


# ---------------------------------------------------------------------------------------------------------
# Storage and resume
# ---------------------------------------------------------------------------------------------------------
class SceneMismatch(ValueError):
    """A results directory that holds another scene's results."""


class DirectoryInUse(ValueError):
    """A results directory that another running study is writing into."""


class TaskStore:
    """The records of finished tasks in ``directory/tasks/`` (``R{r}_U{j}.json``, written atomically) beside
    ``directory/scene.toml``; refuses another scene, and a directory that a running process holds (``run.lock``
    with its process id; a lock of a process that no longer runs, e.g. one that was killed, is taken over).
    :meth:`release` frees the directory."""

    def __init__(self, directory, scene: Scene):
        from .scene import load_scene
        self.directory = Path(directory)
        self.tasks = self.directory / "tasks"
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
            write_atomic(stored, scene.to_toml())
        self.tasks.mkdir(exist_ok=True)
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
            write_atomic(self.lock, str(os.getpid()))                                # a stale lock: taken over
        else:
            with os.fdopen(descriptor, "w") as stream:
                stream.write(str(os.getpid()))

    def release(self) -> None:
        """Free the directory for other runs."""
        self.lock.unlink(missing_ok=True)

    def _path(self, realisation: int, voltage_index: int) -> Path:
        return self.tasks / f"R{realisation:03d}_U{voltage_index:03d}.json"

    def load(self, realisation: int, voltage_index: int) -> tuple | None:
        """The records of task (r, j), or None if it has not finished (or was written with other fields, by
        another version: solved again)."""
        path = self._path(realisation, voltage_index)
        if not path.exists():
            return None
        records = json.loads(path.read_text())
        if any(set(record) != _RECORD_FIELDS for record in records):
            return None
        return tuple(PatchRecord(**{key: tuple(value) if isinstance(value, list) else value
                                    for key, value in record.items()}) for record in records)

    def save(self, realisation: int, voltage_index: int, records: tuple) -> None:
        write_atomic(self._path(realisation, voltage_index), json.dumps([dataclasses.asdict(r) for r in records]))


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:                     # it runs, under another user
        return True
    return True


# ---------------------------------------------------------------------------------------------------------
# Executors: in this process, a local process pool, a dask.distributed cluster
# ---------------------------------------------------------------------------------------------------------
class _Deferred:
    """A task of :class:`_InProcess`: run when its result is asked for."""

    def __init__(self, function, arguments):
        self.function, self.arguments = function, arguments

    def result(self):
        return self.function(*self.arguments)


class _InProcess:
    """Tasks run one after the other in this process, as their results are consumed; FFT threads by
    ``roughcontact.fft``'s default."""
    threads = None

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        return False

    def submit(self, function, *arguments):
        return _Deferred(function, arguments)

    def as_completed(self, futures):
        return iter(futures)


def _start_worker(threads: int, client: int):
    """Pool worker start: ``threads`` FFT threads unless ``$ROUGHCONTACT_FFT_THREADS`` says otherwise; Ctrl-C is
    the client's to handle (it cancels the tasks and stops the workers); the worker ends with the client
    process ``client`` even when that is killed (a worker would otherwise wait for tasks for ever)."""
    import signal
    import threading
    from .fft import THREADS_VARIABLE
    if not os.environ.get(THREADS_VARIABLE):                 # (unset or empty)
        os.environ[THREADS_VARIABLE] = str(threads)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_end_with, args=(client,), daemon=True).start()


def _end_with(client: int) -> None:
    while _running(client):
        time.sleep(1.0)
    os._exit(1)


class _Pool:
    """A local pool of ``workers`` spawned processes with ``fft_threads`` FFT threads each (the numba kernels
    are serial); interrupted, it cancels the waiting tasks and terminates the workers."""
    threads = None                                  # the worker's default, set by _start_worker

    def __init__(self, workers: int, fft_threads: int):
        self.workers, self.fft_threads = workers, fft_threads

    def __enter__(self):
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor
        if "forkserver" in multiprocessing.get_all_start_methods():      # workers forked from a loaded server
            context = multiprocessing.get_context("forkserver")
            context.set_forkserver_preload(["roughcontact.study", "roughcontact.contact"])
        else:
            context = multiprocessing.get_context("spawn")
        self.executor = ProcessPoolExecutor(self.workers, mp_context=context,
                                            initializer=_start_worker, initargs=(self.fft_threads, os.getpid()))
        return self

    def __exit__(self, kind, error, traceback):
        if kind is None:
            self.executor.shutdown()
            return False
        processes = list(self.executor._processes.values())     # (no public way to stop running tasks before 3.14)
        self.executor.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            process.terminate()
        for process in processes:
            process.join()
        return False

    def submit(self, function, *arguments):
        return self.executor.submit(function, *arguments)

    def as_completed(self, futures):
        from concurrent.futures import as_completed
        return as_completed(futures)


class _Dask:
    """The dask.distributed scheduler at ``address``: one FFT thread per task (a worker runs one task per
    thread). The scheduler reruns the tasks of a worker that is lost (up to its ``allowed-failures``);
    interrupted, the client cancels the tasks it submitted."""
    threads = 1

    def __init__(self, address: str):
        try:
            import distributed
        except ImportError:
            raise ImportError("running on a dask cluster needs dask.distributed: pip install 'roughcontact[parallel]'"
                              ) from None
        self.distributed, self.address, self.futures = distributed, address, []

    def __enter__(self):
        try:
            self.client = self.distributed.Client(self.address, set_as_default=False)   # dask's config untouched
        except OSError as error:                                 # no scheduler answers (after its connect timeout)
            raise ValueError(f"dask = {self.address!r}: {error}") from None
        return self

    def __exit__(self, kind, error, traceback):
        if kind is not None:
            self.client.cancel(self.futures)
        self.client.close()
        return False

    def submit(self, function, *arguments):
        future = self.client.submit(function, *arguments)        # pure: a rerun gives the same records
        self.futures.append(future)
        return future

    def as_completed(self, futures):
        return self.distributed.as_completed(futures, loop=self.client.loop)


def _check_executor(workers, dask) -> None:
    """Refuse a bad ``workers`` or both executors (see :func:`run_study`), and ``dask`` without the extra."""
    from surfaces.validation import check_integer
    if workers is not None:
        check_integer("workers", workers, low=1)
    if dask is not None:
        if workers is not None:
            raise ValueError(f"workers = {workers!r} with dask = {dask!r}: the cluster has its own workers; give "
                             "one of the two")
        _Dask(dask)


def _executor(workers, dask, tasks: int):
    """The executor of ``tasks`` tasks (see :func:`run_study`)."""
    if dask is not None:
        return _Dask(dask)
    from .fft import available_cores
    cores = available_cores()
    workers = min(cores, tasks) if workers is None else workers
    if workers == 1 or tasks <= 1:
        return _InProcess()
    return _Pool(workers, max(1, cores // workers))


# ---------------------------------------------------------------------------------------------------------
# The sweep
# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StudyResult:
    """All points of a study; ``points[i][j]`` at ``normal_forces[i]``, ``voltages[j]``; ``coarse_graining``
    the A_R closing diameters [m] (the scene's first); ``computed`` points with a task solved in this run and
    ``solves`` the contact solves of this run; ``short_cutoff`` the micro-roughness cut-off in use [m]."""

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


def run_study(scene: Scene, directory=None, progress: bool = False, workers: int | None = None,
              dask: str | None = None) -> StudyResult:
    """Run (or resume, with a ``directory``) the study of ``scene``; ``progress`` shows a tqdm bar of points.

    The tasks (:func:`solve_chain`, or :func:`roughcontact.coupling.coupled_chain` where the preset's ``scales``
    is "coupled"; one per realisation and voltage) run in a local pool of ``workers``
    processes (default: the cores this process may run on, at most one per task), each task with cores //
    workers FFT threads; ``workers=1`` runs them in this process. ``dask``, the address of a dask.distributed
    scheduler (``"tcp://host:8786"``), runs them on that cluster instead (one FFT thread per task; needs
    ``roughcontact[parallel]``). Every executor gives the same records for the same FFT plans. A script that
    uses the pool needs Python's ``if __name__ == "__main__":`` guard around its work (the workers import it).
    Interrupted (Ctrl-C), the waiting tasks are cancelled and the pool's workers stopped (a cluster's running
    tasks finish and are dropped); the finished ones stay in ``directory``.
    """
    _check_executor(workers, dask)
    store = None if directory is None else TaskStore(directory, scene)
    forces, voltages = scene.loads.normal_forces, scene.loads.voltages
    count = realisation_count(scene)
    cutoff = resolved_short_cutoff(scene) if scene.roughness.enabled else float("nan")
    order = [(r, j) for j in range(len(voltages)) for r in range(count)]
    records = {}
    if store is not None:
        records = {key: done for key in order if (done := store.load(*key)) is not None}
    todo = [key for key in order if key not in records]
    executor = _executor(workers, dask, len(todo)) if todo else _InProcess()
    bar = None
    if progress and todo:
        from tqdm import tqdm
        bar = tqdm(total=len(todo) * len(forces) / count, desc="roughcontact run", unit="point",
                   bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} [{elapsed}<{remaining}]")
    task = solve_chain
    if scene.preset.scales == "coupled":            # the micro-roughness as an interface law (roughcontact.coupling)
        from .coupling import coupled_chain as task
    apparent = apparent_scale(scene)                # once, for every task
    from concurrent.futures.process import BrokenProcessPool
    try:
        with executor:
            futures = {executor.submit(task, scene, r, j, executor.threads, apparent): (r, j) for r, j in todo}
            for future in executor.as_completed(list(futures)):
                key = futures[future]
                records[key] = future.result()
                if store is not None:
                    store.save(*key, records[key])
                if bar is not None:
                    bar.update(len(forces) / count)
    except BrokenProcessPool as error:
        raise RuntimeError("a worker of the study's process pool ended abruptly: killed (e.g. out of memory), or, "
                           "in a script, the pool was started without the 'if __name__ == \"__main__\":' guard "
                           "around the script's work (the workers import the script); add the guard, or run "
                           "in this process with workers=1. Finished tasks are kept in the results "
                           "directory") from error
    finally:
        if bar is not None:
            bar.close()
        if store is not None:
            store.release()
    table = tuple(tuple(_point_result(force, voltage, *apparent[i], [records[(r, j)][i] for r in range(count)])
                        for j, voltage in enumerate(voltages)) for i, force in enumerate(forces))
    return StudyResult(scene=scene, points=table, coarse_graining=_lengths(scene), short_cutoff=cutoff,
                       computed=len({j for _, j in todo}) * len(forces),
                       solves=sum(record.solves for key in todo for record in records[key]))
