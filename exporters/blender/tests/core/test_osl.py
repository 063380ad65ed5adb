"""core/osl.py: what the OSL compiler prints, caught on file descriptors; oslquery's folder."""

import ctypes
import os
import sys

from facet_blender.core import osl


def test_capture_native_catches_what_native_code_prints_and_restores_the_descriptors(capfd):
    libc = ctypes.CDLL(None)
    before = (os.fstat(1).st_ino, os.fstat(2).st_ino)
    with osl.CaptureNative() as capture:
        os.write(1, b"from fd 1\n")
        os.write(2, b"error: from fd 2\n")
        libc.printf(b"from C's printf\n")                 # buffered in C: flushed on the way out
    assert capture.text.splitlines() == ["from fd 1", "error: from fd 2", "from C's printf"]
    assert (os.fstat(1).st_ino, os.fstat(2).st_ino) == before
    os.write(1, b"after\n")
    assert capfd.readouterr().out == "after\n"            # nothing captured leaks out, output is back


def test_compiler_errors_quote_the_errors_and_the_reports():
    printed = "compiling\n/tmp/x.osl:3: error: Syntax error: syntax error\nwarning: unused\n"
    reports = ["OSL query failed", "", "Script compilation succeeded"]
    assert osl.compiler_errors(printed, reports) == ["/tmp/x.osl:3: error: Syntax error: syntax error",
                                                     "OSL query failed"]
    assert osl.compiler_errors("", []) == []
    assert osl.compiler_errors(None, ["Error: no shader"]) == ["Error: no shader"]


def test_site_packages_with_finds_the_folder_holding_the_module(tmp_path):
    for version, has in (("3.11", True), ("3.10", False), ("3.12", True)):
        folder = tmp_path / "lib" / f"python{version}" / "site-packages"
        folder.mkdir(parents=True)
        if has:
            (folder / "oslquery").mkdir()
    (tmp_path / "lib" / "python3.13").mkdir()            # no site-packages
    assert osl.site_packages_with(str(tmp_path), "oslquery") == [
        str(tmp_path / "lib" / "python3.11" / "site-packages"), str(tmp_path / "lib" / "python3.12" / "site-packages")]
    assert osl.site_packages_with(str(tmp_path / "none"), "oslquery") == []
    assert sys.modules.get("bpy", None) is None
