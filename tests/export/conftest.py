import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))


@pytest.fixture(scope="session")
def clips():
    """The default data, converted fresh from the pybullet wheel (not read from public/)."""
    from export.data.sources import default_source
    return {c.name: c for c in default_source().clips()}
