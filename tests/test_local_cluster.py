"""The LocalCluster a map starts carries its Dask settings into the processes that use
them: the scheduler (in this process) and each worker process (through its nanny). A
setting that stayed in the client would pass unnoticed: the map would only be slower
(bench/model_maps.py measures by how much)."""

import dask

from numerics.maps import LOCAL_CLUSTER_CONFIG, local_cluster


def _worker_view(dask_worker):
    """What a worker process was started with: its settings and its periodic callbacks."""
    return {"profile_enabled": dask.config.get("distributed.worker.profile.enabled"),
            "profiling": "profile" in dask_worker.periodic_callbacks}


def test_workers_and_scheduler_start_with_the_map_settings():
    from dask.distributed import Client

    assert dask.config.get("distributed.worker.profile.enabled"), \
        "Dask's own default profiles workers; else this test shows nothing"
    with local_cluster(2) as cluster, Client(cluster) as client:
        views = client.run(_worker_view)
        saturation = client.run_on_scheduler(
            lambda dask_scheduler: dask_scheduler.WORKER_SATURATION)
    assert len(views) == 2
    for view in views.values():
        assert view == {"profile_enabled": False, "profiling": False}
    assert saturation == LOCAL_CLUSTER_CONFIG["distributed.scheduler.worker-saturation"]
    # the settings were the cluster's alone: this process's own stay Dask's defaults
    assert dask.config.get("distributed.worker.profile.enabled")
