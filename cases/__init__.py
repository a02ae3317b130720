"""Case definitions (TOML), their loader and validation, and analytical references."""

from .loader import BUNDLED, load_case, load_point
from .model import Case, CaseError, one_case

__all__ = ["BUNDLED", "Case", "CaseError", "load_case", "load_point", "one_case"]
