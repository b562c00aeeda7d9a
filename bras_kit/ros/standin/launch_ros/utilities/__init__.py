from .._core import evaluate_parameter_dict, make_namespace_absolute, prefix_namespace  # noqa: F401
