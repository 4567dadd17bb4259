"""Map a function over chunks of work: in this process, on local worker processes, or on
a Dask cluster.

``scheduler="dask://HOST:PORT"`` connects a :class:`dask.distributed.Client` to a running
scheduler (``tcp://`` addresses are accepted as they are); ``workers=N`` starts a
:class:`dask.distributed.LocalCluster` of ``N`` single-threaded worker processes for the
call; neither runs everything here, in order. At most ``in_flight`` chunks are submitted
at a time, so the results waiting in memory stay bounded, and the results always come
back in the order of the items, whichever worker finished first. Dask is imported only
when a cluster is asked for (``pip install "powergraph[dask]"``).

Examples
--------
>>> map_chunks(abs, [-2, 3, -5])
[2, 3, 5]
"""
from __future__ import annotations

from contextlib import contextmanager
from typing import Any, Callable, Iterable, Iterator, Sequence

from powergraph.errors import UsageError

SCHEME = "dask://"


def scheduler_address(text: str) -> str:
    """``dask://HOST:PORT`` -> ``tcp://HOST:PORT``; ``tcp://``, ``tls://`` and
    ``inproc://`` addresses are kept.

    >>> scheduler_address("dask://10.0.0.5:8786")
    'tcp://10.0.0.5:8786'
    """
    if text.startswith(SCHEME):
        rest = text[len(SCHEME):]
        if not rest:
            raise UsageError(f"scheduler address '{text}' has no host: use dask://HOST:PORT")
        return "tcp://" + rest
    if text.startswith(("tcp://", "tls://", "inproc://")):
        return text
    raise UsageError(f"scheduler address '{text}' must start with dask:// (dask://HOST:PORT)")


def map_chunks(function: Callable[[Any], Any], items: Iterable[Any], *,
               scheduler: str | None = None, workers: int | None = None,
               in_flight: int | None = None) -> list[Any]:
    """``[function(item) for item in items]``, possibly on a Dask cluster.

    Parameters
    ----------
    function : picklable callable (a module-level function) taking one item
    items : the chunks of work (picklable)
    scheduler : ``dask://HOST:PORT`` of a running Dask scheduler
    workers : start a local cluster of this many worker processes
    in_flight : most chunks submitted at once (default: 4 per worker thread)

    Returns
    -------
    list
        The results in the order of ``items``.
    """
    with cluster(scheduler=scheduler, workers=workers) as run:
        return run(function, items, in_flight)


@contextmanager
def cluster(*, scheduler: str | None = None, workers: int | None = None
            ) -> Iterator[Callable[..., list[Any]]]:
    """A mapper ``run(function, items, in_flight=None) -> list`` on one cluster, kept for
    several maps (a local cluster is started once and closed at the end).

    >>> with cluster() as run:
    ...     run(abs, [-1, 2])
    [1, 2]
    """
    if scheduler is not None and workers is not None:
        raise UsageError("give either a scheduler or a number of workers, not both")
    if workers is not None and (not isinstance(workers, int) or workers < 1):
        raise UsageError(f"workers must be a whole number >= 1, got {workers!r}")
    if scheduler is None and workers is None:
        yield lambda function, items, in_flight=None: [function(item) for item in items]
        return
    address = scheduler_address(scheduler) if scheduler is not None else None
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError as exc:  # pragma: no cover - depends on the installation
        raise UsageError("a Dask cluster needs dask[distributed]: "
                         "pip install 'powergraph[dask]'") from exc
    if address is not None:
        with Client(address) as client:
            yield lambda function, items, in_flight=None: _run(client, function, list(items),
                                                               in_flight)
        return
    with numpy_friendly_workers(), LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True,
            dashboard_address=None) as local, Client(local) as client:
        yield lambda function, items, in_flight=None: _run(client, function, list(items),
                                                           in_flight)


def numpy_friendly_workers() -> Any:
    """Dask's nanny sets ``MALLOC_TRIM_THRESHOLD_`` in the workers it starts (to hand
    freed memory back to the system). Setting it fixes glibc's mmap threshold, so every
    large numpy temporary is mapped and unmapped again: the synthesis ran about twice as
    slowly in such a worker as in this process (measured, docs/synthesis.md). The local
    workers started here keep glibc's default: a ``dask.config.set`` context for
    starting them.

    Examples
    --------
    >>> with numpy_friendly_workers():                          # doctest: +SKIP
    ...     local = LocalCluster(n_workers=2, threads_per_worker=1)
    """
    import dask

    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
    environ.pop("MALLOC_TRIM_THRESHOLD_", None)
    return dask.config.set({"distributed.nanny.pre-spawn-environ": environ})


def _run(client: Any, function: Callable, items: Sequence[Any], in_flight: int | None
         ) -> list[Any]:
    """Submit at most ``in_flight`` items at a time; collect results by index."""
    from dask.distributed import as_completed

    limit = in_flight or 4 * max(1, sum(client.nthreads().values()))
    results: list[Any] = [None] * len(items)
    pending = iter(enumerate(items))

    def submit(entry: tuple[int, Any]) -> Any:
        index, item = entry
        future = client.submit(function, item, pure=False)
        future.index = index  # type: ignore[attr-defined]
        return future

    running = as_completed([submit(e) for _, e in zip(range(limit), pending)])
    for future in running:
        results[future.index] = future.result()
        future.release()
        following = next(pending, None)
        if following is not None:
            running.add(submit(following))
    return results
