"""The searches and studies on an executor: a dask.distributed local cluster (the ``dask`` extra) and a
process pool give exactly the serial results, each task seeded by itself."""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from springlab.design import ground, rank, screen, tolerance
from springlab.errors import SpringlabError
from springlab.executors import check_executor, map_ordered
from springlab.model.armfile import load_arm

ARMS = Path(__file__).resolve().parents[1] / "notebooks" / "arms"


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("dask.distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def _same_report(a, b):
    assert [(d.method, d.configuration, d.springs, d.max_force) for d in a.designs] == \
        [(d.method, d.configuration, d.springs, d.max_force) for d in b.designs]
    assert a.rejected == b.rejected and a.configurations_tried == b.configurations_tried and a.notes == b.notes


def test_design_search_on_a_dask_cluster_is_the_serial_one(client):
    spec = load_arm(ARMS / "paper000_arm.toml")
    serial = rank.design_arm(spec, max_designs=3, restarts=4, force_starts=1)
    spread = rank.design_arm(spec, max_designs=3, restarts=4, force_starts=1, executor=client.get_executor(), batch=4)
    _same_report(serial, spread)
    assert serial.designs[0].spring_count == 3  # the ground springs, found first


def test_screen_and_tolerance_study_on_a_dask_cluster(client):
    executor = client.get_executor()
    chain = load_arm(ARMS / "paper000_arm.toml").chain()
    assert ground.relaxation_screen(chain, 3, executor=executor) == ground.relaxation_screen(chain, 3)
    candidates = screen.any_sign_candidates(4, 3)
    assert screen.screen(chain, candidates, executor=executor) == screen.screen(chain, candidates)
    assert any(screen.screen(chain, candidates))  # some sets of three pass the relaxation: the check can see a difference
    springs = rank.design_arm(ARMS / "paper000_arm.toml", max_designs=1).designs[0].springs
    X = rank.random_poses(chain, 50, 1)
    tol = tolerance.Tolerances(attachment=1e-3, stiffness=0.02)
    a = tolerance.tolerance_study(chain, springs, X, tol, samples=20, seed=3, progress=False)
    b = tolerance.tolerance_study(chain, springs, X, tol, samples=20, seed=3, progress=False, executor=executor)
    assert a.torques.keys() == b.torques.keys() and all(np.array_equal(a.torques[k], b.torques[k]) for k in a.torques)
    c = tolerance.tolerance_study(chain, springs, X, tol, samples=20, seed=4, progress=False, executor=executor)
    assert not np.array_equal(a.torques["all"], c.torques["all"])  # another seed, other arms


def test_a_process_pool_and_bad_executors():
    spec = load_arm(ARMS / "paper000_arm.toml")
    with ProcessPoolExecutor(2) as pool:
        spread = rank.design_arm(spec, method="no auxiliary links", max_designs=2, max_configurations=5, restarts=4,
                                 force_starts=1, executor=pool, batch=3)
    serial = rank.design_arm(spec, method="no auxiliary links", max_designs=2, max_configurations=5, restarts=4,
                             force_starts=1)
    _same_report(serial, spread)
    chain = spec.chain()
    with ProcessPoolExecutor(2) as pool:
        spread = ground.fewer_springs(chain, 3, restarts=4, samples=200, executor=pool)
    serial = ground.fewer_springs(chain, 3, restarts=4, samples=200)
    assert [(d.configuration, d.springs) for d in spread] == [(d.configuration, d.springs) for d in serial] and serial
    assert map_ordered(None, divmod, [(7, 2), (9, 4)]) == [(3, 1), (2, 1)]
    with pytest.raises(SpringlabError, match="executor"):
        check_executor("four cores")
    with pytest.raises(SpringlabError, match="executor"):
        rank.design_arm(spec, executor=8)
