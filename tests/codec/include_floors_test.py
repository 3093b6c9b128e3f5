#!/usr/bin/env python3
"""The floors of the code, read from its #include lines.

Inside codec/src each folder is a floor and includes only its own folder
and the floors below it (core at the bottom, mesh above it; only pgc/
names the PGC baseline, and nothing below the pipeline includes pgc/).
The decoder library's sources, and every codec/src header they reach,
include no encoder header. Code outside the codec (protocol, server,
client, tools, web) reaches codec/src only through meshwave_core, that is
"core/..." headers.

    include_floors_test.py SOURCE_DIR
"""
import pathlib
import re
import sys

# Floors, bottom first; folders on one floor do not include each other.
FLOORS = [
    ["core", "image"],
    ["mesh"],
    ["semiregular", "entropy", "asset"],
    ["bitplane", "connectivity"],
    ["wavelet", "analysis", "texture", "attributes", "original"],
    ["quant"],
    ["stream", "metrics"],
    ["pgc", "remesh"],
    ["pipeline"],
]
RANK = {folder: rank for rank, floor in enumerate(FLOORS) for folder in floor}
# Headers only an encoder includes (its half of a scheme).
ENCODER_HEADER = re.compile(
    r'^(entropy/arithmetic_encoder\.h|bitplane/encoder_io\.h|.*_encoder\.h|.*_encoder_io\.h|'
    r'wavelet/sawt_choice\.h|stream/stream_preparation\.h|stream/stream_format_writer\.h|'
    r'stream/distortion_index_writer\.h|pgc/.*|remesh/.*|analysis/.*|metrics/.*|quant/subband_gains\.h|'
    r'quant/deadzone_choice\.h|asset/.*|image/.*)$')
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def includes(path):
    return INCLUDE.findall(path.read_text(errors="replace"))


def decoder_sources(root):
    cmake = (root / "codec/CMakeLists.txt").read_text()
    block = cmake[cmake.index("add_library(meshwave_decoder"):]
    block = block[:block.index("if(MESHWAVE_DECODER_ONLY)")]
    return sorted(set(re.findall(r"(src/[\w/]+\.cpp)", block)))


def main(root):
    root = pathlib.Path(root)
    src = root / "codec/src"
    problems = []
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".h", ".cpp"):
            continue
        folder = path.relative_to(src).parts[0]
        if folder not in RANK:
            problems.append(f"{path.relative_to(root)}: folder {folder} has no floor in this test")
            continue
        for inc in includes(path):
            target = inc.split("/")[0]
            if target not in RANK or "/" not in inc:
                continue
            if target != folder and RANK[target] >= RANK[folder]:
                problems.append(f"{path.relative_to(root)}: includes {inc}, not below {folder}/")

    # The decoder reaches no encoder header, directly or through a header.
    for source in decoder_sources(root):
        seen, todo = set(), [src / source[len("src/"):]]
        while todo:
            path = todo.pop()
            for inc in includes(path):
                if ENCODER_HEADER.match(inc):
                    problems.append(f"codec/{source}: reaches the encoder's {inc} "
                                    f"(through {path.relative_to(root)})")
                header = src / inc
                if header.exists() and header not in seen:
                    seen.add(header)
                    todo.append(header)
        for inc in includes(src / source[len("src/"):]):
            if (root / "codec/include/encoder" / inc).exists():
                problems.append(f"codec/{source}: includes the encoder's public {inc}")
    for header in sorted((root / "codec/include/decoder").rglob("*.h")):
        for inc in includes(header):
            if not (root / "codec/include/decoder" / inc).exists():
                problems.append(f"{header.relative_to(root)}: includes {inc}, not a decoder header")

    # Above the codec: codec/src only as core/ (meshwave_core).
    for area in ("protocol", "server", "client", "tools", "web"):
        for path in sorted((root / area).rglob("*")):
            if path.suffix not in (".h", ".cpp") or "vendor" in path.parts:
                continue
            for inc in includes(path):
                target = inc.split("/")[0]
                if target in RANK and target != "core" and (src / inc).exists():
                    problems.append(f"{path.relative_to(root)}: includes the codec's internal {inc}")

    for p in problems:
        print("FAIL:", p)
    if not problems:
        print(f"ok: {len(decoder_sources(root))} decoder sources; every include keeps to its floor")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
