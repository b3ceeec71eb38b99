"""lang/record.py's `record` against the witness it imitates: classes that
`dataclasses.dataclass(frozen=True)` itself makes from the same fields. Equality, hash (the
same number, so sets iterate in the same order), repr, immutability and the dataclass
helpers must all agree, for generated field specs and for every record class of the AST
and the IR."""

from __future__ import annotations

import dataclasses
import inspect
import math
from dataclasses import FrozenInstanceError, field
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.lang import ir
from rmot.lang import ast
from rmot.lang.record import record

# one field: (compare, hash, repr); hash None = follow compare, as dataclass defaults
SPEC = st.tuples(st.booleans(), st.sampled_from([None, True, False]), st.booleans())
VALUE = st.one_of(st.integers(-3, 3), st.sampled_from(["a", "b", ""]), st.none(),
                  st.sampled_from([0.0, -0.0, 1.5, math.inf, math.nan]),
                  st.tuples(st.integers(0, 2), st.integers(0, 2)))


def _twins(specs: list[tuple[bool, bool | None, bool]], slots: bool,
           kw_only: bool) -> tuple[type, type]:
    """The same class twice: once by `record`, once by dataclass(frozen=True)."""
    def body() -> dict[str, Any]:
        ns: dict[str, Any] = {"__annotations__": {f"f{i}": "Any" for i in range(len(specs))}}
        for i, (compare, hash_, repr_) in enumerate(specs):
            ns[f"f{i}"] = field(compare=compare, hash=hash_, repr=repr_)
        return ns
    mine = record(slots=slots, kw_only=kw_only)(type("Twin", (), body()))
    witness = dataclasses.dataclass(frozen=True, slots=slots, kw_only=kw_only)(
        type("Twin", (), body()))
    return mine, witness


@settings(max_examples=300, deadline=None)
@given(specs=st.lists(SPEC, max_size=5), slots=st.booleans(), kw_only=st.booleans(),
       data=st.data())
def test_record_behaves_as_a_frozen_dataclass(specs: list[tuple[bool, bool | None, bool]],
                                              slots: bool, kw_only: bool,
                                              data: st.DataObject) -> None:
    mine, witness = _twins(specs, slots, kw_only)
    names = [f"f{i}" for i in range(len(specs))]
    a_vals = {n: data.draw(VALUE) for n in names}
    b_vals = {n: data.draw(st.one_of(st.just(a_vals[n]), VALUE)) for n in names}
    a, b = mine(**a_vals), mine(**b_vals)
    wa, wb = witness(**a_vals), witness(**b_vals)
    assert (a == b) == (wa == wb)
    assert (a != b) == (wa != wb)
    assert (a == a) == (wa == wa)  # nan fields: identity first, as in a tuple
    assert hash(a) == hash(wa) and hash(b) == hash(wb)
    assert repr(a) == repr(wa) and repr(b) == repr(wb)
    assert (a == wa) is False and a.__eq__(wa) is NotImplemented  # another class
    assert [f.name for f in dataclasses.fields(a)] == names
    assert dataclasses.asdict(a) == dataclasses.asdict(wa)
    if names:
        with pytest.raises(FrozenInstanceError):
            setattr(a, names[0], 1)
        assert dataclasses.replace(a, **{names[0]: 7}) == mine(**{**a_vals, names[0]: 7})
    assert hasattr(a, "__dict__") is (not slots)
    assert list(inspect.signature(mine).parameters) == list(inspect.signature(witness).parameters)


def test_a_set_of_records_iterates_in_the_witness_order() -> None:
    mine, witness = _twins([(True, None, True), (False, None, False)], True, False)
    values = [(i * 7919 % 101, str(i)) for i in range(200)]
    assert ([x.f0 for x in {mine(*v) for v in values}]
            == [x.f0 for x in {witness(*v) for v in values}])


def test_recursion_in_repr_is_cut_as_dataclass_cuts_it() -> None:
    mine, witness = _twins([(True, None, True)], False, False)
    loop: list[Any] = []
    witness_loop: list[Any] = []
    a, wa = mine(loop), witness(witness_loop)
    loop.append(a)
    witness_loop.append(wa)
    assert repr(a) == "Twin(f0=[...])" == repr(wa)


def test_a_class_with_its_own_equality_is_refused() -> None:
    class Own:
        x: int

        def __eq__(self, other: object) -> bool:
            return True

    with pytest.raises(TypeError, match="shared"):
        record(Own)


RECORDS = [c for m in (ast, ir) for c in vars(m).values()
           if isinstance(c, type) and c.__module__ == m.__name__ and dataclasses.is_dataclass(c)]


def test_the_ast_and_ir_are_records() -> None:
    assert len(RECORDS) >= 100
    shared = (ir.Pose.__eq__.__code__, ir.Pose.__hash__.__code__)
    assert all((c.__eq__.__code__, c.__hash__.__code__) == shared for c in RECORDS)


@pytest.mark.parametrize("cls", RECORDS, ids=lambda c: f"{c.__module__}.{c.__qualname__}")
def test_every_ast_and_ir_class_agrees_with_its_dataclass_twin(cls: type) -> None:
    every = dataclasses.fields(cls)
    witness = dataclasses.make_dataclass(
        cls.__name__, [(f.name, Any, field(compare=f.compare, hash=f.hash, repr=f.repr))
                       for f in every], frozen=True, slots=True)
    witness.__qualname__ = cls.__qualname__
    args = {f.name: (i * 31 % 7, f.name) for i, f in enumerate(every)}
    other = {**args, **{f.name: 0 for f in every[-1:]}}
    a, b, wa, wb = (_raw(cls, args), _raw(cls, other), _raw(witness, args),
                    _raw(witness, other))
    assert hash(a) == hash(wa) and repr(a) == repr(wa)
    assert (a == b) == (wa == wb) and (a == _raw(cls, args)) is True
    with pytest.raises(FrozenInstanceError):
        setattr(a, every[0].name, None)


def _raw(cls: type, values: dict[str, Any]) -> Any:
    """An instance with these field values, past __init__ and its __post_init__ checks
    (the values are placeholders, not valid poses or targets)."""
    obj = object.__new__(cls)
    for name, value in values.items():
        object.__setattr__(obj, name, value)
    return obj
