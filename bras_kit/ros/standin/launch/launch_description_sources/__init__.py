from .._core import InvalidPythonLaunchFileError  # noqa: F401
from .._sources import (  # noqa: F401
    AnyLaunchDescriptionSource,
    FrontendLaunchDescriptionSource,
    LaunchDescriptionSource,
    PythonLaunchDescriptionSource,
    XMLLaunchDescriptionSource,
    YAMLLaunchDescriptionSource,
    get_launch_description_from_any_launch_file,
    get_launch_description_from_python_launch_file,
    load_python_launch_file_as_module,
)
