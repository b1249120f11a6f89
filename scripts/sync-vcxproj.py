#!/usr/bin/env python3
"""Rewrites the ClCompile/ClInclude items of every mapped .vcxproj from the source lists CMake
writes at generate time (<build>/sources/<target>.txt, see Tests/Platform/CMakeLists.txt), so the
Visual Studio projects list exactly what CMake builds. The vcxproj_sync test checks the result.

Usage: scripts/sync-vcxproj.py [build-dir]     (default build/native; configure it first)
A new target still needs its .vcxproj, a .sln entry and an SR_VCXPROJ_MAP line by hand."""
import os
import re
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "native")
lists = os.path.join(build, "sources")
if not os.path.isdir(lists):
    sys.exit(f"sync-vcxproj: {lists} not found: configure that build first (cmake --preset native)")

HEADER_EXT = (".hpp", ".h", ".inl")
changed = 0
for name in sorted(os.listdir(lists)):
    if name.startswith("@") or not name.endswith(".txt"):
        continue
    lines = open(os.path.join(lists, name), encoding="utf-8").read().splitlines()
    meta = dict(l.split("=", 1) for l in lines[:3])
    sources = [l for l in lines[3:] if l.strip()]
    if not meta.get("source_dir"):
        continue  # target not part of this build (e.g. SoftRaster natively)
    proj = os.path.join(root, meta["vcxproj"])
    proj_dir = os.path.dirname(proj)
    items = []
    for s in sources:
        path = s if os.path.isabs(s) else os.path.join(meta["source_dir"], s)
        rel = os.path.relpath(path, proj_dir).replace("/", "\\")
        kind = "ClInclude" if rel.lower().endswith(HEADER_EXT) else "ClCompile"
        items.append((kind, rel))
    raw = open(proj, encoding="utf-8", newline="").read()
    crlf = "\r\n" in raw
    text = raw.replace("\r\n", "\n")
    # Drop the existing source item groups, then insert one compile and one include group
    # before the first ProjectReference group (or before the Import of Cpp.targets).
    body = re.sub(r"  <ItemGroup>\n(?:    <Cl(?:Compile|Include) Include=\"[^\"]*\" />\n)+  </ItemGroup>\n", "", text)
    groups = ""
    for kind in ("ClCompile", "ClInclude"):
        entries = [f'    <{kind} Include="{rel}" />\n' for k, rel in items if k == kind]
        if entries:
            groups += "  <ItemGroup>\n" + "".join(entries) + "  </ItemGroup>\n"
    anchor = body.find("  <ItemGroup>\n    <ProjectReference")
    if anchor < 0:
        anchor = body.find('  <Import Project="$(VCTargetsPath)\\Microsoft.Cpp.targets"')
    if anchor < 0:
        sys.exit(f"sync-vcxproj: cannot find where to put the items in {proj}")
    new = body[:anchor] + groups + body[anchor:]
    if new != text:
        open(proj, "w", encoding="utf-8", newline="").write(new.replace("\n", "\r\n") if crlf else new)
        changed += 1
        print(f"updated {meta['vcxproj']}")
print(f"sync-vcxproj: {changed} project(s) updated")
