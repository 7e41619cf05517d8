"""The tiny study scene and its in-process result, shared by the study and execution tests."""
import pytest

from roughcontact.study.run import run_study
from roughcontact.study.scene import load_scene
from study_scenes import TINY


@pytest.fixture(scope="session")
def tiny():
    return load_scene(text=TINY, preset="draft")


@pytest.fixture(scope="session")
def tiny_result(tiny):
    return run_study(tiny, workers=1)
