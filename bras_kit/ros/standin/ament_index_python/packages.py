"""Packages are the resources of type 'packages' (packages.py): a package's prefix, its share
folder, and PackageNotFoundError in ROS's words when no prefix lists it."""

import os
import pathlib
import re
import warnings

from .resources import get_resource, get_resources
from .search_paths import get_search_paths

# REP 127's package names, with its recommended exemptions (packages.py, get_package_prefix)
_PACKAGE_NAME = re.compile('[a-zA-Z0-9][a-zA-Z0-9_-]+', re.ASCII)


class PackageNotFoundError(KeyError):
    pass


def get_packages_with_prefixes():
    """{package name: prefix} for every installed package."""
    return get_resources('packages')


def get_package_prefix(package_name):
    """The install prefix holding ``package_name`` ('.../install/PKG' in a colcon workspace)."""
    if _PACKAGE_NAME.fullmatch(package_name) is None:
        raise ValueError(f"'{package_name}' is not a valid package name")
    try:
        return get_resource('packages', package_name)[1]
    except LookupError:
        raise PackageNotFoundError(f"package '{package_name}' not found, searching: {get_search_paths()}") from None


def get_package_share_directory(package_name, print_warning=True):
    """PREFIX/share/PKG, as a string; a warning (not an error) when that folder is missing."""
    share = os.path.join(get_package_prefix(package_name), 'share', package_name)
    if print_warning and not os.path.exists(share):
        warnings.warn(f'Share directory for {package_name} ({share}) does not exist.', stacklevel=2)
    return share


def get_package_share_path(package_name, print_warning=True):
    """The share folder as a pathlib.Path (``get_package_share_path('pkg') / 'urdf/bras.urdf'``)."""
    share = pathlib.Path(get_package_share_directory(package_name, print_warning=False))
    if print_warning and not share.exists():
        warnings.warn(f'Share path for {package_name} ({share}) does not exist.', stacklevel=2)
    return share
