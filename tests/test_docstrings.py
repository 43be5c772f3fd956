"""Every public callable is documented in numpydoc (issue 16).

The rules are in ``tests/docstring_rules.py``: numpydoc's own validator for a
docstring, every parameter in Parameters and nothing else, Returns or Yields when a
value comes back; and units in brackets for parameters whose names carry a unit.
"""

from docstring_rules import all_problems, problems, public_callables


def test_the_rules_catch_an_undocumented_function(tmp_path, monkeypatch):
    """The check can fail: a module with a bare function and one with a unit-suffixed
    parameter described without its unit both report problems, and a documented one
    none."""
    pkg = tmp_path / "docprobe"
    pkg.mkdir()
    (pkg / "__init__.py").write_text(
        'def bare(x_m):\n    return x_m\n\n\n'
        'def unitless(x_m):\n    """Twice a length.\n\n    Parameters\n    ----------\n'
        '    x_m : float\n        A length.\n\n    Returns\n    -------\n    float\n'
        '        Twice it [m].\n    """\n    return 2 * x_m\n\n\n'
        'def good(x_m):\n    """Twice a length.\n\n    Parameters\n    ----------\n'
        '    x_m : float\n        A length [m].\n\n    Returns\n    -------\n    float\n'
        '        Twice it [m].\n    """\n    return 2 * x_m\n')
    monkeypatch.syspath_prepend(str(tmp_path))
    assert public_callables(["docprobe"]) == ["docprobe.bare", "docprobe.unitless",
                                              "docprobe.good"]
    assert problems("docprobe.bare")
    assert problems("docprobe.unitless")
    assert problems("docprobe.good") == []


def test_every_public_callable_has_numpydoc_parameters_and_returns():
    found = all_problems()
    assert not found, f"{len(found)} problems:\n" + "\n".join(found[:60])
