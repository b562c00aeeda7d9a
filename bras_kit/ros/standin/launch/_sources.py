"""launch/launch_description_sources/*.py (Jazzy): a Python launch file is loaded as a module and
its ``generate_launch_description()`` called; XML and YAML files go through the frontend."""

from __future__ import annotations

import os
from importlib.machinery import SourceFileLoader
from importlib.util import module_from_spec, spec_from_loader
from typing import Any

from ._core import (
    InvalidPythonLaunchFileError,
    LaunchContext,
    LaunchDescription,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)


def load_python_launch_file_as_module(python_launch_file_path: str) -> Any:
    """python_launch_file_utilities.py"""
    basename = os.path.basename(python_launch_file_path)
    loader = SourceFileLoader(basename.replace('.', '_'), python_launch_file_path)
    spec = spec_from_loader(loader.name, loader)
    if spec is None:
        raise RuntimeError('Failed to load module spec!')
    mod = module_from_spec(spec)
    loader.exec_module(mod)
    return mod


def get_launch_description_from_python_launch_file(python_launch_file_path: str) -> LaunchDescription:
    module = load_python_launch_file_as_module(python_launch_file_path)
    if not hasattr(module, 'generate_launch_description'):
        raise InvalidPythonLaunchFileError(
            "launch file at '{}' does not contain the required function '{}'".format(
                python_launch_file_path, 'generate_launch_description()'))
    return module.generate_launch_description()


def get_launch_description_from_any_launch_file(launch_file_path: str) -> LaunchDescription:
    """any_launch_file_utilities.py:30: the loader the extension names first, then the other; when
    both fail, one InvalidLaunchFileError lists what each said (ros2 launch prints that list)."""
    loaders: list[Any] = [_frontend_loader]
    extension = os.path.splitext(os.path.basename(launch_file_path))[1][1:]
    if extension == 'py':
        loaders.insert(0, get_launch_description_from_python_launch_file)
    else:
        loaders.append(get_launch_description_from_python_launch_file)
        if extension not in ('xml', 'yaml', 'yml'):  # Parser.is_filename_valid
            extension = ''
    errors: list[BaseException] = []
    for loader in loaders:
        try:
            return loader(launch_file_path)
        except Exception as exc:  # noqa: BLE001 - kept, as launch keeps it
            errors.append(exc)
    from ._frontend import InvalidLaunchFileError

    raise InvalidLaunchFileError(extension, likely_errors=errors)


def _frontend_loader(launch_file_path: str) -> LaunchDescription:
    """The XML and YAML front ends, imported when a file needs them (a Python launch file that
    loads never does: the parsers are a sixth of a launch file's evaluation)."""
    from ._frontend import get_launch_description_from_frontend_launch_file

    return get_launch_description_from_frontend_launch_file(launch_file_path)


class LaunchDescriptionSource:
    """launch_description_source.py"""

    def __init__(self, launch_description: LaunchDescription | None = None,
                 location: str = '<script>', method: str = 'interpreted python launch file') -> None:
        self._launch_description = launch_description
        self.__location: Any = normalize_to_list_of_substitutions(location)
        self.__expanded_location: str | None = None
        self.__method = method

    @property
    def location(self) -> str:
        if self.__expanded_location is None:
            return ' + '.join(s.describe() for s in self.__location)
        return self.__expanded_location

    @property
    def method(self) -> str:
        return self.__method

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        return self._launch_description

    def _load(self, path: str) -> LaunchDescription:
        return get_launch_description_from_any_launch_file(path)

    def get_launch_description(self, context: LaunchContext) -> LaunchDescription:
        if self._launch_description is None:
            self.__expanded_location = perform_substitutions(context, self.__location)
            if not os.path.exists(self.__expanded_location):
                raise FileNotFoundError(
                    f"[Errno 2] No such file or directory: '{self.__expanded_location}'")
            self._launch_description = self._load(self.__expanded_location)
        return self._launch_description


class PythonLaunchDescriptionSource(LaunchDescriptionSource):
    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(None, launch_file_path, 'interpreted python launch file')

    def _load(self, path: str) -> LaunchDescription:
        return get_launch_description_from_python_launch_file(path)


class FrontendLaunchDescriptionSource(LaunchDescriptionSource):
    def __init__(self, launch_file_path: Any, *, parser: Any = None) -> None:
        super().__init__(None, launch_file_path, 'interpreted frontend launch file')


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(None, launch_file_path, 'interpreted launch file')


XMLLaunchDescriptionSource = FrontendLaunchDescriptionSource
YAMLLaunchDescriptionSource = FrontendLaunchDescriptionSource
