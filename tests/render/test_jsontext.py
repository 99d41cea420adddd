"""render/jsontext.py writes what json.dumps(indent, sort_keys, ensure_ascii=False) writes, byte for byte
(the oracle is the standard library), and a Streamed list as the list it streams."""

from __future__ import annotations

import enum
import json
import random

import pytest

from canspec.render.jsontext import Streamed, dumps

VALUES = [
    None, True, False, 0, -1, 2**64 + 1, 0.1, -0.0, 1e22, 1e-7, float("nan"), float("inf"), float("-inf"),
    "", "a\"b\\c\n\t\x00\x1f\x7f", "中文 ünïcode \u2028", [], {}, (), [[]], {"": {}},
]


class Code(enum.IntEnum):
    A = 3


def _oracle(obj: object, indent: int = 1) -> str:
    return json.dumps(obj, indent=indent, sort_keys=True, ensure_ascii=False)


def _random_value(rng: random.Random, depth: int) -> object:
    pick = rng.randrange(9 if depth < 4 else 5)
    if pick < 5:
        return rng.choice(VALUES[:16])
    if pick < 7:
        return [_random_value(rng, depth + 1) for _ in range(rng.randrange(4))]
    return {rng.choice(["b", "a", "kind", "Z", "é", "a1"]): _random_value(rng, depth + 1) for _ in range(rng.randrange(4))}


@pytest.mark.parametrize("value", VALUES, ids=repr)
def test_scalars_and_empty_containers(value: object) -> None:
    assert dumps(value) == _oracle(value)
    assert dumps({"k": value, "l": [value]}, indent=2) == _oracle({"k": value, "l": [value]}, indent=2)


def test_random_nesting_matches_json() -> None:
    rng = random.Random(25)
    for _ in range(300):
        value = _random_value(rng, 0)
        assert dumps(value) == _oracle(value)


def test_subclasses_and_non_string_keys() -> None:
    value = {1: Code.A, 2.5: True, "x": [Code.A, 1.5]}
    assert dumps({str(k): v for k, v in value.items()}) == _oracle({str(k): v for k, v in value.items()})
    assert dumps({3: "i", 1: "j"}) == _oracle({3: "i", 1: "j"})
    assert dumps({True: 1}) == _oracle({True: 1})


def test_streamed_list_is_the_list() -> None:
    items = [{"raw": {"a": 1}, "kind": "zero"}, {"raw": {}, "kind": "max"}]
    assert dumps({"cases": Streamed(iter(items)), "about": 1}) == _oracle({"cases": items, "about": 1})
    assert dumps({"cases": Streamed(iter([]))}) == _oracle({"cases": []})


def test_not_serializable_is_a_type_error() -> None:
    with pytest.raises(TypeError):
        dumps({"x": object()})
    with pytest.raises(TypeError):
        dumps({(1, 2): 0})


def test_equal_keys_of_other_types_in_one_text() -> None:
    value = [{1: "int"}, {True: "bool"}, {1.0: "float"}, {"1": "str"}]
    assert dumps(value) == _oracle(value)
