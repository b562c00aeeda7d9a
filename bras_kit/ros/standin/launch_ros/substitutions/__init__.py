from .._core import ExecutableInPackage, FindPackage, FindPackagePrefix, FindPackageShare  # noqa: F401
