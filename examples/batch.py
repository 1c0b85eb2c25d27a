"""Meshes every CAD file of folders or glob patterns, a few at a time, each
in a process of its own, with a progress bar; writes OUTDIR/summary.csv (the
columns of `sizemesh batch`). Options after -- go to every file's run.

    /usr/bin/python3 examples/batch.py models/ 'more/*.stp' -o out --jobs 2 [-- --phi-c 10]
"""
import concurrent.futures
import os
import sys

from tqdm import tqdm

from batch_common import cad_files, find_sizemesh, mesh_one, parse, stems, write_summary


def main():
    a = parse(sys.argv[1:], __doc__,
              lambda ap: ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count(), help="files at once"))
    sizemesh = find_sizemesh(a.sizemesh)
    files = cad_files(a.inputs)
    names = stems(files)
    rows = [None] * len(files)
    # Threads are enough: each file runs in a process of its own.
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        futures = {pool.submit(mesh_one, sizemesh, f, a.output, s, a.format, a.timeout, a.options): i
                   for i, (f, s) in enumerate(zip(files, names))}
        with tqdm(total=len(files), unit="file") as bar:
            for done in concurrent.futures.as_completed(futures):
                rows[futures[done]] = done.result()
                bar.update()
    write_summary(a.output, rows)
    return 0 if all(r["status"] == "ok" for r in rows) else 3


if __name__ == "__main__":
    sys.exit(main())
