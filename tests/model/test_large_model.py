"""A large model (a 20,000-gear chain) loads and is built correctly (linear algorithms:
no per-link scan of all components; the benchmark benchmarks/large_model.py times it)."""
from __future__ import annotations

from powergraph.model import loads_model
from powergraph.testing_trains import gear_chain_text


def chain_text(n: int) -> str:
    """A fixed-axis chain: gear i meshes gear i + 1, carrier = the frame."""
    return gear_chain_text(n, input_port="")


def test_a_20000_gear_chain_is_one_body_per_gear_and_every_mesh_on_the_frame() -> None:
    n = 20_000
    model = loads_model(chain_text(n))
    assert len(model.bodies) == n + 1 and len(model.meshes) == n - 1
    assert {link.carrier for link in model.meshes} == {"0"}
    assert model.links[-1].between == (str(n - 1), str(n))
    assert model.components[str(n)].teeth == 20 + n % 7
    assert model.body(str(n)).members == (str(n),) and model.frame_body == "0"
