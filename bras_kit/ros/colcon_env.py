"""The environment files colcon writes in a package's prefix: hooks, package scripts, as data.

After a package is built, colcon-core asks each environment extension which variable the prefix
extends (colcon_core/environment/__init__.py, create_environment_hooks, lines 179-205 of
colcon-core 0.21.3) and writes one hook per primary shell for each (colcon_core/shell/__init__.py,
create_environment_hook, lines 414-480): ``share/PKG/hook/NAME.ps1``, ``.dsv`` and ``.sh``, in
that order (powershell's priority 300, then dsv and sh at 200 by name). Then one package script per
shell lists those hooks (create_environment_scripts_only, lines 95-156): ``package.bash``,
``package.dsv``, ``package.ps1``, ``package.sh``, ``package.zsh``. colcon-ros adds
``ament_prefix_path`` (AMENT_PREFIX_PATH, the prefix itself) before setup.py runs
(colcon_ros/task/ament_python/build.py, lines 39-41 of colcon-ros 0.5.0), so a package whose
setup.py fails still leaves that hook.

The ``.dsv`` files are colcon's data (``prepend-non-duplicate;VAR;VALUE``, ``source;PATH``) and
are written as colcon writes them. The shell scripts are bras-kit's own text with the behaviour of
colcon's: each hook calls ``_colcon_prepend_unique_value VAR VALUE`` (the function colcon's scripts
define, so its setup scripts and these source each other), ``package.sh`` defines it and sources
the hooks in package.dsv's order, ``package.bash``/``.zsh`` find the prefix from their own path
and source ``package.sh``. The tests source both colcon's and these and compare what they export.
"""

from __future__ import annotations

import os
import shlex
from dataclasses import dataclass

__all__ = ["Hook", "hook_files", "package_scripts", "prefix_hooks", "PRIMARY_SHELLS"]

PRIMARY_SHELLS = ("ps1", "dsv", "sh")  # colcon's order: powershell (300), then dsv and sh (200) by name
MARK = "# written by bras-kit build"


@dataclass(frozen=True)
class Hook:
    """One environment hook: ``name`` (its file name), the ``variable`` it prepends to, and the
    ``value``: "" for the prefix itself, a folder relative to it, or an absolute path."""

    name: str
    variable: str
    value: str


def prefix_hooks(prefix: str, package: str, python_lib: str) -> list[Hook]:
    """The hooks colcon's environment extensions find in a laid-out prefix, in their order (by
    entry point name: colcon_core/plugin_system.py, order_extensions_by_priority, lines 91-106)."""
    hooks: list[Hook] = []
    # cmake_module_path (colcon_cmake/environment/cmake_module_path.py): Find*.cmake in the
    # package's CMake folders
    found: list[str] = []
    for folder in _cmake_module_folders(package):
        full = os.path.join(prefix, folder)
        if os.path.isdir(full) and any(n.startswith("Find") and n.endswith(".cmake")
                                       and os.path.isfile(os.path.join(full, n)) for n in os.listdir(full)):
            if not any(os.path.samefile(full, os.path.join(prefix, f)) for f in found):
                hooks.append(Hook("cmake_module_path" + (str(len(found)) if found else ""), "CMAKE_MODULE_PATH",
                                  folder))
                found.append(folder)
    # cmake_prefix_path (colcon_cmake/environment/cmake_prefix_path.py): any *Config.cmake file
    if any(n.endswith(("-config.cmake", "Config.cmake")) for _d, _s, names in os.walk(prefix) for n in names):
        hooks.append(Hook("cmake_prefix_path", "CMAKE_PREFIX_PATH", ""))
    # library_path (colcon_library_path/environment/library_path.py): a lib* folder holding *.so
    for folder in sorted(n for n in _names(prefix) if n.startswith("lib")):
        full = os.path.join(prefix, folder)
        if os.path.isdir(full) and any(n.endswith(".so") for n in os.listdir(full)):
            hooks.append(Hook(f"ld_library_path_{folder}", "LD_LIBRARY_PATH", folder))
    # path (colcon_core/environment/path.py, PathEnvironment): bin/ holding a file
    if _has_file(os.path.join(prefix, "bin")):
        hooks.append(Hook("path", "PATH", "bin"))
    # pkg_config (colcon_pkg_config/environment/pkg_config.py): lib/pkgconfig/PKG.pc
    if os.path.isfile(os.path.join(prefix, "lib", "pkgconfig", package + ".pc")):
        hooks.append(Hook("pkg_config", "PKG_CONFIG_PATH", "lib/pkgconfig"))
    # pythonpath (colcon_core/environment/pythonpath.py): the purelib folder exists
    if os.path.exists(os.path.join(prefix, python_lib)):
        hooks.append(Hook("pythonpath", "PYTHONPATH", python_lib))
    # pythonscriptspath (colcon_core/environment/path.py, PythonScriptsPathEnvironment): the
    # scheme's scripts folder, bin/ under a prefix
    if _has_file(os.path.join(prefix, "bin")):
        hooks.append(Hook("pythonscriptspath", "PATH", "bin"))
    return hooks


def _names(folder: str) -> list[str]:
    try:
        return os.listdir(folder)
    except OSError:
        return []


def _has_file(folder: str) -> bool:
    return os.path.isdir(folder) and any(os.path.isfile(os.path.join(folder, n)) for n in os.listdir(folder))


def _cmake_module_folders(package: str) -> list[str]:
    """CMake's find_package locations colcon-cmake looks in (cmake_module_path.py, lines 50-90)."""
    libs = ("lib64", "lib32", "libx32", "lib")
    return ([f"{lib}/cmake/{package}" for lib in libs] + [f"share/cmake/{package}"]
            + [f"{lib}/{package}" for lib in libs] + [f"share/{package}"]
            + [f"{lib}/{package}/cmake" for lib in libs] + [f"{lib}/{package}/CMake" for lib in libs]
            + [f"share/{package}/cmake", f"share/{package}/CMake"])


def hook_files(package: str, hook: Hook) -> list[tuple[str, bytes]]:
    """``share/PKG/hook/NAME.ps1``, ``.dsv`` and ``.sh``: (path relative to the prefix, text)."""
    folder = f"share/{package}/hook/{hook.name}"
    if os.path.isabs(hook.value):
        sh, ps1 = f'"{_sh_safe(hook.value)}"', f'"{_ps1_safe(hook.value)}"'
    else:
        sh = '"$COLCON_CURRENT_PREFIX' + (f"/{_sh_safe(hook.value)}" if hook.value else "") + '"'
        ps1 = '"$env:COLCON_CURRENT_PREFIX' + (f"/{_ps1_safe(hook.value)}" if hook.value else "") + '"'
    return [
        (f"{folder}.ps1", f"{MARK}: prepends to {hook.variable}\n\ncolcon_prepend_unique_value "
                          f"{hook.variable} {ps1}\n".encode()),
        # colcon_core/shell/template/hook_prepend_value.dsv.em: one line, the value as given
        (f"{folder}.dsv", f"prepend-non-duplicate;{hook.variable};{hook.value}\n".encode()),
        (f"{folder}.sh", f"{MARK}: prepends to {hook.variable}\n\n_colcon_prepend_unique_value "
                         f"{hook.variable} {sh}\n".encode()),
    ]


def _sh_safe(relative: str) -> str:
    """A folder relative to the prefix inside a double-quoted shell word: what expands escaped."""
    return "".join("\\" + c if c in '"$`\\' else c for c in relative)


def _ps1_safe(relative: str) -> str:
    return "".join("`" + c if c in '"$`' else c for c in relative)


def package_scripts(package: str, prefix: str, hooks: list[str]) -> list[tuple[str, bytes]]:
    """``share/PKG/package.{bash,dsv,ps1,sh,zsh}`` for the hook files ``hooks`` (relative to the
    prefix, in their order), as (path relative to the prefix, text)."""
    share = f"share/{package}"
    dsv = "".join(f"source;{hook}\n" for hook in hooks)  # colcon_core/shell/template/package.dsv.em
    sh_hooks = "".join(f'_bras_kit_source "$COLCON_CURRENT_PREFIX/{_sh_safe(h)}"\n'
                       for h in hooks if h.endswith(".sh"))
    ps1_hooks = "".join(f'_bras_kit_source "$env:COLCON_CURRENT_PREFIX/{_ps1_safe(h)}"\n'
                        for h in hooks if h.endswith(".ps1"))
    return [
        (f"{share}/package.bash", PACKAGE_BASH.format(mark=MARK, share=_sh_safe(share)).encode()),
        (f"{share}/package.dsv", dsv.encode()),
        (f"{share}/package.ps1", PACKAGE_PS1.format(mark=MARK, hooks=ps1_hooks).encode()),
        (f"{share}/package.sh", PACKAGE_SH.format(mark=MARK, prefix=shlex.quote(prefix), hooks=sh_hooks).encode()),
        (f"{share}/package.zsh", PACKAGE_ZSH.format(mark=MARK, share=_sh_safe(share)).encode()),
    ]


# What colcon's package.sh does (colcon_core/shell/template/package.sh.em): prepend each value once,
# keep the others in their order, drop empty ones; the prefix is COLCON_CURRENT_PREFIX when set, else
# the build-time prefix. The loop splits on ':' by parameter expansion, so it runs alike in sh, bash and zsh.
PACKAGE_SH = """{mark}: the environment of this package, as colcon's package.sh sets it

_colcon_prepend_unique_value() {{
  eval "_bras_kit_rest=\\"\\${{$1:-}}\\""
  _bras_kit_all="$2"
  while [ -n "$_bras_kit_rest" ]; do
    _bras_kit_item="${{_bras_kit_rest%%:*}}"
    case "$_bras_kit_rest" in
      *:*) _bras_kit_rest="${{_bras_kit_rest#*:}}" ;;
      *) _bras_kit_rest="" ;;
    esac
    if [ -n "$_bras_kit_item" ] && [ "$_bras_kit_item" != "$2" ]; then
      _bras_kit_all="$_bras_kit_all:$_bras_kit_item"
    fi
  done
  eval "export $1=\\"\\$_bras_kit_all\\""
  unset _bras_kit_rest _bras_kit_all _bras_kit_item
}}

if [ -z "$COLCON_CURRENT_PREFIX" ]; then
  COLCON_CURRENT_PREFIX={prefix}
  if [ ! -d "$COLCON_CURRENT_PREFIX" ]; then
    echo "The build time path \\"$COLCON_CURRENT_PREFIX\\" doesn't exist. Either source a script for a different shell or set the environment variable \\"COLCON_CURRENT_PREFIX\\" explicitly." 1>&2
    unset COLCON_CURRENT_PREFIX
    return 1
  fi
fi

_bras_kit_source() {{
  if [ -f "$1" ]; then
    if [ -n "$COLCON_TRACE" ]; then
      echo "# . \\"$1\\""
    fi
    . "$1"
  else
    echo "not found: \\"$1\\"" 1>&2
  fi
}}

{hooks}
unset -f _bras_kit_source
unset COLCON_CURRENT_PREFIX
"""

# package.bash and package.zsh differ only in how the shell names the sourced file's own path
_PACKAGE_SOURCES_SH = """{{mark}}: finds this package's prefix from its own path, then sources package.sh

if [ -z "$COLCON_CURRENT_PREFIX" ]; then
  _bras_kit_prefix="$(builtin cd {cd}"$(dirname "{own_path}")/../.." > /dev/null && pwd)"
else
  _bras_kit_prefix="$COLCON_CURRENT_PREFIX"
fi
if [ -f "$_bras_kit_prefix/{{share}}/package.sh" ]; then
  COLCON_CURRENT_PREFIX="$_bras_kit_prefix" . "$_bras_kit_prefix/{{share}}/package.sh"
else
  echo "not found: \\"$_bras_kit_prefix/{{share}}/package.sh\\"" 1>&2
fi
unset _bras_kit_prefix
"""
PACKAGE_BASH = _PACKAGE_SOURCES_SH.format(cd="", own_path="${{BASH_SOURCE[0]}}")
PACKAGE_ZSH = _PACKAGE_SOURCES_SH.format(cd="-q ", own_path="${{(%):-%N}}")

PACKAGE_PS1 = """{mark}: the environment of this package, as colcon's package.ps1 sets it

function colcon_prepend_unique_value {{
  param ($_listname, $_value)
  $_all = @($_value)
  if (Test-Path Env:$_listname) {{
    $_all += (Get-Item env:$_listname).Value.Split(":") | Where-Object {{ $_ -and $_ -ne $_value }}
  }}
  Set-Item env:\\$_listname -Value ($_all -join ":")
}}

function _bras_kit_source {{
  param ($_script)
  if (Test-Path $_script) {{ . "$_script" }} else {{ Write-Error "not found: '$_script'" }}
}}

$env:COLCON_CURRENT_PREFIX=(Get-Item $PSCommandPath).Directory.Parent.Parent.FullName
{hooks}
Remove-Item Env:\\COLCON_CURRENT_PREFIX
"""
