"""The batch the concurrency tests run, as a script so each way of running it has a process
(and a process group) of its own that a test can kill if it hangs.

    python batch_work.py fork|threads|nested|dask

runs the batch one item at a time in this process first (so the parent has used bumpmap, and
its threads, before any fork), then the way named; prints the timings and exits 0 when every
item equals the one-at-a-time result, 1 when one differs.
"""

import multiprocessing
import sys
import time
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np

import bumpmap

BATCH = 50


def work(i):
    """One item: a normal map of its own heights, tangents of a small grid, and a render."""
    heights = bumpmap.read_height_field(f"dimples@{32 + (i % 4) * 8}")
    normals = bumpmap.normal_map(heights, scale=2 + i % 3)
    n = 6
    u, v = np.meshgrid(np.linspace(0, 1, n, dtype=np.float32), np.linspace(0, 1, n, dtype=np.float32))
    positions = np.stack([u, v, 0.1 * np.sin(3 * u + i)], axis=-1).reshape(-1, 3)
    quads = [(y * n + x, y * n + x + 1, (y + 1) * n + x + 1, (y + 1) * n + x) for y in range(n - 1) for x in range(n - 1)]
    indices = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.uint32)
    uvs = np.stack([u, v], axis=-1).reshape(-1, 2)
    mesh = bumpmap.tangents(positions, None, uvs, indices)
    image = bumpmap.render(backend="cpu", size=24, scene="sphere", technique="single-pass", bump_scale=1 + i % 4)
    return normals, mesh["tangents"], image


def forked(items, workers=2):
    with ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("fork")) as pool:
        return list(pool.map(work, items))


def nested(items):
    """A forked child that uses bumpmap and then forks in turn."""
    work(0)
    return forked(items, workers=1)


def threads(items):
    with ThreadPoolExecutor(max_workers=4) as pool:
        return list(pool.map(work, items))


def dask(items):
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            return client.gather(client.map(work, items))


def main(way):
    items = list(range(BATCH))
    start = time.perf_counter()
    serial = [work(i) for i in items]
    print(f"{BATCH} items one at a time: {time.perf_counter() - start:.2f} s")
    start = time.perf_counter()
    if way == "nested":
        with ProcessPoolExecutor(max_workers=1, mp_context=multiprocessing.get_context("fork")) as pool:
            got = pool.submit(nested, items).result()
    else:
        got = {"fork": forked, "threads": threads, "dask": dask}[way](items)
    print(f"{BATCH} items, {way}: {time.perf_counter() - start:.2f} s")
    bad = [i for i, (a, b) in enumerate(zip(got, serial)) if not all(np.array_equal(x, y) for x, y in zip(a, b))]
    if bad or len(got) != len(serial):
        print(f"items {bad} differ from one at a time")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
