"""Every command's ``--json`` validates against its schema in ``docs/schemas/``.

The schemas are the contract scripts read: each names the keys a command's JSON always
has and the type of each (a number may be null where the quantity is undefined, e.g. a
water rate of a card doing no work).  A key renamed, dropped or changed in type fails
here before a user's script does.
"""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest

from corliss.cli import commands as cli

ROOT = Path(__file__).resolve().parent.parent
SCHEMAS = ROOT / "docs" / "schemas"

HUNTING_SCENE = "porter-allen-governor"


def _schema(name: str) -> dict:
    return json.loads((SCHEMAS / f"{name}.schema.json").read_text(encoding="utf-8"))


def _json_of(argv: list[str], capsys) -> object:
    rc = cli.main(argv)
    out = capsys.readouterr()
    assert rc in (0, 4), out.err
    return json.loads(out.out)


@pytest.fixture(scope="module")
def card(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("card")
    assert cli.main(["run", "default", "--out", str(out), "--no-plots", "--fidelity",
                     "fast"]) == 0
    return out / "default.cards.csv"


def _commands(tmp: Path, card: Path) -> dict[str, list[list[str]]]:
    o = ["--out", str(tmp)]
    return {
        "run": [["run", "default", "--json", "--no-plots", "--fidelity", "fast", *o],
                ["run", HUNTING_SCENE, "--json", "--no-plots", "--fidelity", "fast",
                 "--duration", "1 s", *o]],
        "events": [["events", "default", "--json"],
                   ["events", "walschaerts-locomotive", "--json", "--settings", "0.5,1"],
                   ["events", "default", "--json", "--units", "US"],
                   ["events", "walschaerts-locomotive", "--settings", "0.5,1", "--units", "SI"]],
        "design": [["design", "--cutoff", "0.6", "--lead", "0.25in", "--max-opening", "1.25in",
                    "--json", *o],
                   ["design", "porter-allen-engine", "--cutoff", "0.3", "--json", *o]],
        "sweep": [["sweep", "porter-allen-engine", "--settings", "0.3,1", "--fidelity", "fast",
                   "--json", *o]],
        "compare": [["compare", "armington-sims-governor", "--loads", "1",
                     "--with-condensation", "off", "--fidelity", "fast", "--json", *o]],
        "study": [["study", "default", "--vary", "valve_gear.lap=0.8:1.2in", "--grid",
                   "--levels", "2", "--fidelity", "fast", "--jobs", "1", "--json", *o]],
        "fit": [["fit", "default", str(card), "--vary", "valve_gear.lap=0.9:1.1in", "--json",
                 "--no-plots", *o]],
    }


@pytest.mark.parametrize("command", ["run", "events", "design", "sweep", "compare", "study",
                                     "fit"])
def test_every_commands_json_validates_against_its_schema(command, tmp_path, card, capsys):
    schema = _schema(command)
    jsonschema.Draft202012Validator.check_schema(schema)
    for argv in _commands(tmp_path, card)[command]:
        jsonschema.validate(_json_of(argv, capsys), schema)


def test_a_schema_refuses_a_renamed_key():
    """The check can fail: the steady summary without its indicated power is refused."""
    schema = _schema("run")
    steady = schema["oneOf"][0]
    doc = {k: None for k in steady["required"] if k != "indicated_power_W"}
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate({**doc, "kind": "steady", "title": "x"}, schema)
