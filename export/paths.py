"""Where things live in the repository; every command resolves paths through here."""
from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PUBLIC = ROOT / "public"
CLIPS_DIR = PUBLIC / "clips"
MODELS_DIR = PUBLIC / "models"
CONTRACT_DIR = ROOT / "contract"
VECTORS_DIR = CONTRACT_DIR / "vectors"
CONFIGS_DIR = ROOT / "configs"
RUNS_DIR = ROOT / "runs"
DOCS_DIR = ROOT / "docs"
