from .._core import normalize_to_list_of_substitutions, perform_substitutions  # noqa: F401
