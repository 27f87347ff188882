#!/usr/bin/env python3
"""Checks that the peer programs of `make bench-peers` draw Facet's scene (a CTest).

Runs facet_bench's BM_Sphere and each given peer on the same sphere and asserts that they
cover the same pixels (to 0.1 %: the peers sample pixel centers as Facet does, so a
different count means a different camera, mesh or image size), and that bandwidth_bench
measures a positive bandwidth.

    /usr/bin/python3 bench/check_peers.py build/bin osmesa_peer embree_peer
"""
import json
import subprocess
import sys
from pathlib import Path

TRIANGLES = 20000


def run_program(path, *args):
    """The JSON object a bench program prints last, or None when it was not built."""
    if not Path(path).is_file():
        return None
    result = subprocess.run([str(path), *map(str, args)], check=True, capture_output=True,
                            text=True)
    return json.loads(result.stdout.strip().splitlines()[-1])


def coverage_disagreement(counts):
    """A message when the covered pixel counts {name: count} differ by more than 0.1 %."""
    known = {name: n for name, n in counts.items() if n is not None}
    if known and max(known.values()) - min(known.values()) > 0.001 * max(known.values()):
        return f"covered pixels differ: {known}"
    return None


def facet_pixels(bin_dir):
    result = subprocess.run(
        [str(bin_dir / "facet_bench"),
         f"--benchmark_filter=BM_Sphere/triangles:{TRIANGLES}/threads:2/closed:0",
         "--benchmark_format=json"], check=True, capture_output=True, text=True)
    return int(json.loads(result.stdout)["benchmarks"][0]["pixels"])


def main():
    bin_dir, peers = Path(sys.argv[1]), sys.argv[2:]
    bandwidth = run_program(bin_dir / "bandwidth_bench", "--mib", 64, "--passes", 2)
    assert bandwidth["read_bytes_per_second"] > 0 and bandwidth["write_bytes_per_second"] > 0, \
        bandwidth
    counts = {"facet_bench": facet_pixels(bin_dir)}
    for peer in peers:
        report = run_program(bin_dir / peer, "--triangles", TRIANGLES, "--frames", 1)
        if report is None:
            sys.exit(f"{bin_dir / peer} was not built")
        counts[peer] = report["pixels_covered"]
    problem = coverage_disagreement(counts)
    if problem:
        sys.exit(problem)
    print(f"{TRIANGLES} triangles, covered pixels agree: {counts}; bandwidth {bandwidth}")


if __name__ == "__main__":
    main()
