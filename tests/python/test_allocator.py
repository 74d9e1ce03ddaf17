# Tests python/allocator.cpp: in a process whose environment froze glibc's
# mmap threshold the way a Dask worker's does (MALLOC_TRIM_THRESHOLD_ set),
# importing gpm puts blocks of 0.2-1 MB (the calibration's matrices) back on
# the heap; elsewhere it changes nothing.
import os
import subprocess
import sys

import pytest

# Allocates blocks of 1 MB through glibc and prints how many of them became
# mappings of their own (mallinfo2's hblks) and what gpm says it did.
PROBE = r"""
import ctypes, sys
class MallInfo2(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in
                ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks",
                 "keepcost")]
libc = ctypes.CDLL("libc.so.6")
libc.malloc.restype = ctypes.c_void_p
libc.free.argtypes = [ctypes.c_void_p]
libc.mallinfo2.restype = MallInfo2
set_by_gpm = None
if sys.argv[1] == "import":
    import gpm
    set_by_gpm = gpm._large_blocks_on_the_heap
before = libc.mallinfo2().hblks
blocks = [libc.malloc(1 << 20) for _ in range(8)]
mapped = libc.mallinfo2().hblks - before
for b in blocks:
    libc.free(b)
print(mapped, set_by_gpm)
"""


def probe(env_extra, what):
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    env.update(env_extra)
    out = subprocess.run([sys.executable, "-c", PROBE, what], env=env, capture_output=True, text=True, check=True)
    mapped, set_by_gpm = out.stdout.split()
    return int(mapped), set_by_gpm


def test_a_dask_workers_environment_maps_every_large_block_without_gpm():
    assert probe({"MALLOC_TRIM_THRESHOLD_": "65536"}, "no import") == (8, "None")


def test_importing_gpm_puts_them_back_on_the_heap():
    assert probe({"MALLOC_TRIM_THRESHOLD_": "65536"}, "import") == (0, "True")


def test_elsewhere_gpm_leaves_the_allocator_alone():
    # glibc's own dynamic threshold starts at 128 KiB too: a first 1 MB block is mapped either way.
    assert probe({}, "import")[1] == "False"
    assert probe({"MALLOC_TRIM_THRESHOLD_": "65536", "MALLOC_MMAP_THRESHOLD_": "131072"}, "import") == (8, "False")
