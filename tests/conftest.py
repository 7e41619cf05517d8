import importlib.util
import os
import sys
from pathlib import Path

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")
# the suite is about answers, not speed: instant FFTW plans and one thread (tests/roughcontact/test_fft.py checks
# the library's own defaults, measured plans on every core, with the wisdom cache)
os.environ.setdefault("ROUGHCONTACT_FFTW_PLANNER", "FFTW_ESTIMATE")
os.environ.setdefault("ROUGHCONTACT_FFT_THREADS", "1")

STUDIES = Path(__file__).resolve().parents[1] / "studies"


@pytest.fixture(scope="session", autouse=True)
def wisdom_cache(tmp_path_factory):
    """The FFTW wisdom cache of the session: a fresh directory, not the user's ``~/.cache/roughcontact``, whose
    plans (from any earlier run) would decide whether a test's measured plan adds wisdom."""
    path = tmp_path_factory.mktemp("fftw-wisdom")
    previous, os.environ["ROUGHCONTACT_CACHE"] = os.environ.get("ROUGHCONTACT_CACHE"), str(path)
    yield path
    if previous is None:
        del os.environ["ROUGHCONTACT_CACHE"]
    else:
        os.environ["ROUGHCONTACT_CACHE"] = previous


@pytest.fixture(scope="session")
def load_experiment():
    """``load_experiment(name)`` imports the script ``studies/<name>.py`` as the module ``name``, registered in
    ``sys.modules`` (dataclasses look their module up there); ``studies/`` is put on the path, as ``python
    studies/<name>.py`` does, so that a script imports its siblings (``_bench``, ``field_check``)."""
    if str(STUDIES) not in sys.path:
        sys.path.insert(0, str(STUDIES))

    def load(name):
        if name not in sys.modules:
            spec = importlib.util.spec_from_file_location(name, STUDIES / f"{name}.py")
            sys.modules[name] = module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
        return sys.modules[name]
    return load


@pytest.fixture(scope="session")
def fast_run(load_experiment, tmp_path_factory):
    """``fast_run(name)`` runs ``studies/<name>.py`` in fast mode (``--fast --output <new tmp dir>``) and
    returns that directory."""
    def run(name):
        path = tmp_path_factory.mktemp(name)
        load_experiment(name).main(["--fast", "--output", str(path)])
        return path
    return run


@pytest.fixture(scope="session")
def read_csv():
    """``read_csv(path)``: the rows of a CSV file as dicts of strings, after checking its provenance line."""
    from roughcontact.io import read_csv as read_rows

    def read(path):
        with open(path) as stream:
            assert stream.readline().startswith("# roughcontact ")
        return read_rows(path)
    return read
