import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))


@pytest.fixture(scope="session")
def default_clips():
    """The default data (CMU split by person + DeepMimic train-only), converted fresh (not read from public/)."""
    from export.data.sources import default_source
    return {c.name: c for c in default_source().clips()}


@pytest.fixture(scope="session")
def clips(default_clips):
    """The clips a test works on: the default data, unless a module says otherwise."""
    return default_clips


@pytest.fixture(scope="session")
def deepmimic():
    """The DeepMimic clips alone with their own split (the walker takes test-only, two test tails), under
    their own names: small and fast, for tests that train tiny models or check the DeepMimic conversion."""
    from export.data.sources import DeepMimicSource
    return {c.name: c for c in DeepMimicSource().clips()}
