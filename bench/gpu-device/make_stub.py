#!/usr/bin/env python3
"""bench/gpu-device/make_stub.py — a stand-in for a shared library that no code path of the
carried programs calls (gpu-device-pack.sh): the same SONAME, the same version nodes and the same
exported dynamic symbols (functions, objects of the same size, TLS objects), so that a
BIND_NOW load of a library that links it succeeds without carrying it or its own dependencies.

A stub function prints "<soname>: stub for <symbol> called" and aborts, so a wrong guess shows
up as a message naming the symbol rather than as a wrong result. Symbols named with --benign
return a pointer to a zero-filled static block instead (a "" string, a 0 number): for the
version queries a library calls while it registers its plugins.

    make_stub.py REAL_LIBRARY OUT_DIR [--needed FILE] [--benign SYMBOL ...]

--needed FILE: export only the symbols named in FILE (whitespace-separated names, no versions):
the ones the carried programs and libraries leave undefined. Every version node is kept.
"""
import os
import re
import subprocess
import sys
import tempfile


def readelf(*args):
    return subprocess.run(["readelf", "-W", *args], check=True, capture_output=True,
                          text=True).stdout


def version_definitions(lib):
    """The version nodes the library defines, less the base (its file name), in order."""
    nodes, base = [], None
    text = readelf("-V", lib)
    section = text.split("Version definition section")
    if len(section) < 2:
        return nodes
    body = section[1].split("Version needs section")[0].split("Version symbols section")[0]
    for line in body.splitlines():
        m = re.search(r"Flags: (\S+).*Name: (\S+)", line)
        if m:
            if "BASE" in m.group(1):
                base = m.group(2)
            elif m.group(2) not in nodes:
                nodes.append(m.group(2))
    return [n for n in nodes if n != base]


def defined_symbols(lib):
    """(name, version or None, is_default, type, size) of every defined dynamic symbol."""
    out = []
    for line in readelf("--dyn-syms", lib).splitlines():
        f = line.split()
        if len(f) < 8 or not f[0].endswith(":") or f[0] == "Num:":
            continue
        _, _, size, typ, bind, _, ndx, name = f[:8]
        if ndx in ("UND", "ABS") or bind == "LOCAL" or typ in ("SECTION", "FILE"):
            continue
        if name in ("_init", "_fini", "_edata", "_end", "__bss_start"):
            continue
        version, default = None, True
        if "@@" in name:
            name, version = name.split("@@", 1)
        elif "@" in name:
            name, version = name.split("@", 1)
            default = False
        size = int(size, 0) if size.startswith("0x") else int(size)
        out.append((name, version, default, typ, size))
    return out


def main():
    args = sys.argv[1:]
    benign, needed = set(), None
    if "--needed" in args:
        i = args.index("--needed")
        with open(args[i + 1]) as f:
            needed = set(f.read().split())
        del args[i:i + 2]
    if "--benign" in args:
        i = args.index("--benign")
        benign = set(args[i + 1:])
        args = args[:i]
    lib, out_dir = args
    soname = None
    for line in readelf("-d", lib).splitlines():
        m = re.search(r"\(SONAME\).*\[(.*)\]", line)
        if m:
            soname = m.group(1)
    soname = soname or os.path.basename(lib)
    nodes = version_definitions(lib)
    symbols = defined_symbols(lib)
    if needed is not None:
        symbols = [s for s in symbols if s[0] in needed]

    asm = ['\t.text']
    names = ['\t.section .rodata.stubnames,"a"']
    data = []
    script_nodes = {n: [] for n in nodes}
    unversioned = []
    seen = set()
    for i, (name, version, default, typ, size) in enumerate(symbols):
        key = (name, version, default)
        if key in seen:
            continue
        seen.add(key)
        label = name if default else f"__stub_alias_{i}"
        q = f'"{label}"'
        if typ in ("FUNC", "IFUNC", "NOTYPE") and (typ != "NOTYPE" or size == 0):
            asm += [f"\t.globl {q}", f"\t.type {q},@function", f"{q}:"]
            if name in benign:
                asm += ["\tleaq __stub_zero(%rip), %rax", "\tret"]
            else:
                asm += [f"\tleaq .Lname{i}(%rip), %rdi", "\tjmp __stub_fail"]
            names.append(f'.Lname{i}:\t.asciz "{name}"')
        elif typ == "TLS":
            data += ['\t.section .tbss,"awT",@nobits', "\t.balign 16", f"\t.globl {q}",
                     f"\t.type {q},@tls_object", f"\t.size {q},{size}", f"{q}:",
                     f"\t.zero {max(size, 1)}"]
        else:  # OBJECT, COMMON, GNU_UNIQUE
            data += ['\t.bss', "\t.balign 16", f"\t.globl {q}", f"\t.type {q},@object",
                     f"\t.size {q},{size}", f"{q}:", f"\t.zero {max(size, 1)}"]
        if not default:
            asm.append(f'\t.symver {q},"{name}@{version}"')
            if version not in script_nodes:
                script_nodes[version] = []
        elif version:
            script_nodes.setdefault(version, []).append(name)
        else:
            unversioned.append(name)

    os.makedirs(out_dir, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        s_file = os.path.join(tmp, "stub.s")
        with open(s_file, "w") as f:
            f.write("\n".join(asm + data + names) + "\n")
            f.write('\t.section .note.GNU-stack,"",@progbits\n')
        c_file = os.path.join(tmp, "fail.c")
        with open(c_file, "w") as f:
            f.write(
                "#include <stdio.h>\n#include <stdlib.h>\n"
                "__attribute__((visibility(\"hidden\"))) const char __stub_zero[4096];\n"
                "__attribute__((visibility(\"hidden\"), noreturn)) void __stub_fail(const char* s) {\n"
                f"  fprintf(stderr, \"{soname}: stub for %s called: the pack left this library"
                " out (bench/gpu-device-pack.sh)\\n\", s);\n  abort();\n}\n")
        map_file = os.path.join(tmp, "stub.map")
        with open(map_file, "w") as f:
            if script_nodes:
                first = True
                for node, syms in script_nodes.items():
                    local = "local: *;\n" if first else ""
                    first = False
                    glob = "".join(f'  "{s}";\n' for s in syms + (unversioned if local else []))
                    f.write(f"{node} {{\n" + (f"global:\n{glob}" if glob else "") + local + "};\n")
            else:
                glob = "".join(f'  "{s}";\n' for s in unversioned)
                f.write("{\n" + (f"global:\n{glob}" if glob else "") + "local: *;\n};\n")
        out = os.path.join(out_dir, soname)
        subprocess.run(["gcc", "-shared", "-fPIC", "-O1", "-o", out, s_file, c_file,
                        f"-Wl,-soname,{soname}", f"-Wl,--version-script={map_file}",
                        "-Wl,--no-undefined", "-s"], check=True)
    print(f"{soname}: stub with {len(seen)} symbols, {len(script_nodes)} version nodes")


if __name__ == "__main__":
    main()
