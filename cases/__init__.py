"""Case definitions (TOML), their loader and validation, and analytical references."""

from .loader import BUNDLED, load_case
from .model import Case, CaseError

__all__ = ["BUNDLED", "Case", "CaseError", "load_case"]
