"""ament_index_python as a learner's launch file and node meet it: where an installed package
lives, found from the ament resource index of the prefixes in AMENT_PREFIX_PATH (the install
tree bras-kit build lays out). Written for bras-kit after ament/ament_index (branch jazzy,
ament_index_python 1.8): the same names, results and error words, cited per function."""

from .constants import AMENT_PREFIX_PATH_ENV_VAR, RESOURCE_INDEX_SUBFOLDER
from .packages import (
    PackageNotFoundError,
    get_package_prefix,
    get_package_share_directory,
    get_package_share_path,
    get_packages_with_prefixes,
)
from .resources import (
    InvalidResourceNameError,
    InvalidResourceTypeNameError,
    get_resource,
    get_resource_types,
    get_resources,
    has_resource,
)
from .search_paths import get_search_paths

__all__ = ['AMENT_PREFIX_PATH_ENV_VAR', 'InvalidResourceNameError', 'InvalidResourceTypeNameError',
           'PackageNotFoundError', 'RESOURCE_INDEX_SUBFOLDER', 'get_package_prefix',
           'get_package_share_directory', 'get_package_share_path', 'get_packages_with_prefixes',
           'get_resource', 'get_resource_types', 'get_resources', 'get_search_paths', 'has_resource']
