"""The resource index: one folder per resource type, one file per resource, in each prefix
(resources.py). The first prefix that holds a resource wins."""

import os

from .constants import RESOURCE_INDEX_SUBFOLDER
from .search_paths import get_search_paths


class InvalidResourceTypeNameError(ValueError):
    """A resource type name holding a path separator."""


class InvalidResourceNameError(ValueError):
    """A resource name holding a path separator."""


def _check(resource_type, resource_name=None):
    # the index keeps types as folders and resources as files: no separator in either name
    assert resource_type, 'The resource type must not be empty'
    if '/' in resource_type or '\\' in resource_type:
        raise InvalidResourceTypeNameError(f"Resource type '{resource_type}' is invalid")
    if resource_name is None:
        return
    assert resource_name, 'The resource name must not be empty'
    if '/' in resource_name or '\\' in resource_name:
        raise InvalidResourceNameError(f"Resource name '{resource_name}' is invalid")


def _entry(prefix, *parts):
    return os.path.join(prefix, RESOURCE_INDEX_SUBFOLDER, *parts)


def has_resource(resource_type, resource_name):
    """The first prefix holding the resource, else False."""
    _check(resource_type, resource_name)
    return next((prefix for prefix in get_search_paths() if os.path.isfile(_entry(prefix, resource_type,
                                                                                   resource_name))), False)


def get_resource(resource_type, resource_name):
    """(the resource file's text, its prefix); LookupError when no prefix holds it."""
    prefix = has_resource(resource_type, resource_name)
    if prefix is False:
        raise LookupError(f"Could not find the resource '{resource_name}' of type '{resource_type}'")
    try:
        with open(_entry(prefix, resource_type, resource_name)) as handle:
            return handle.read(), prefix
    except OSError as exc:
        raise OSError(f"Could not open the resource '{resource_name}' of type '{resource_type}':\n{exc}") from exc


def get_resources(resource_type):
    """{resource name: the first prefix that holds it}; folders and dot files are not resources."""
    _check(resource_type)
    found = {}
    for prefix in get_search_paths():
        folder = _entry(prefix, resource_type)
        if not os.path.isdir(folder):
            continue
        for name in os.listdir(folder):
            if not name.startswith('.') and not os.path.isdir(os.path.join(folder, name)):
                found.setdefault(name, prefix)
    return found


def get_resource_types():
    """The resource types (folders of the index) of every prefix, as a set."""
    types = set()
    for prefix in get_search_paths():
        index = _entry(prefix)
        if os.path.isdir(index):
            types |= {name for name in os.listdir(index)
                      if not name.startswith('.') and os.path.isdir(os.path.join(index, name))}
    return types
