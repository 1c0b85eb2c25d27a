"""The batch of examples/batch.py on a Dask cluster: one task per CAD file,
each running the sizemesh command in a process of its own on a worker (a bad
file cannot take a worker down), the rows gathered into OUTDIR/summary.csv.

    /usr/bin/python3 examples/dask_batch.py models/ -o out              # a local cluster of 2 workers
    /usr/bin/python3 examples/dask_batch.py models/ -o out --scheduler tcp://head:8786

With --scheduler it joins an existing Dask deployment, for instance one
started on a Slurm cluster by dask-jobqueue (SLURMCluster(...).scheduler_address);
the workers must see the same paths (a shared file system) and the sizemesh
command (--sizemesh).
"""
import os
import sys

from dask.distributed import Client, LocalCluster, as_completed

from batch_common import cad_files, find_sizemesh, mesh_one, parse, stems, write_summary


def cluster_options(ap):
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: a local cluster)")
    ap.add_argument("--workers", type=int, default=2, help="workers of the local cluster")


def main():
    a = parse(sys.argv[1:], __doc__, cluster_options)
    sizemesh = find_sizemesh(a.sizemesh)
    files = [os.path.abspath(f) for f in cad_files(a.inputs)]
    names = stems(files)
    outdir = os.path.abspath(a.output)
    if a.scheduler:
        client = Client(a.scheduler)
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    with client:
        futures = [client.submit(mesh_one, sizemesh, f, outdir, s, a.format, a.timeout, a.options, pure=False)
                   for f, s in zip(files, names)]
        index = {f.key: i for i, f in enumerate(futures)}
        rows = [None] * len(files)
        for done, row in as_completed(futures, with_results=True):
            rows[index[done.key]] = row
            print("dask: %s %s" % (row["status"], os.path.basename(row["file"])), flush=True)
    write_summary(outdir, rows)
    return 0 if all(r["status"] == "ok" for r in rows) else 3


if __name__ == "__main__":
    sys.exit(main())
