# Copyright 2015 Open Source Robotics Foundation, Inc.
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

from .constants import RESOURCE_INDEX_SUBFOLDER
from .packages import get_package_prefix
from .packages import get_package_share_directory
from .packages import get_package_share_path
from .packages import get_packages_with_prefixes
from .packages import PackageNotFoundError
from .resources import get_resource
from .resources import get_resource_types
from .resources import get_resources
from .resources import has_resource
from .resources import InvalidResourceNameError
from .resources import InvalidResourceTypeNameError
from .search_paths import get_search_paths

__all__ = [
    'get_package_prefix',
    'get_package_share_directory',
    'get_package_share_path',
    'get_packages_with_prefixes',
    'get_resource',
    'get_resources',
    'get_search_paths',
    'get_resource_types',
    'has_resource',
    'InvalidResourceTypeNameError',
    'InvalidResourceNameError',
    'PackageNotFoundError',
    'RESOURCE_INDEX_SUBFOLDER',
]
