import importlib.util
import os
import sys
from pathlib import Path

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")

EXPERIMENTS = Path(__file__).resolve().parents[1] / "experiments"


@pytest.fixture(scope="session")
def load_experiment():
    """``load_experiment(name)`` imports the script ``experiments/<name>.py`` as the module ``name``, registered in
    ``sys.modules`` (dataclasses look their module up there; the scripts import each other by name)."""
    def load(name):
        if name not in sys.modules:
            spec = importlib.util.spec_from_file_location(name, EXPERIMENTS / f"{name}.py")
            sys.modules[name] = module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
        return sys.modules[name]
    return load
