#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Rewrites, in schema/report.schema.json, the definition of every result block
whose struct declares its fields (result_fields.hpp; the module lists them in
_core._result_fields()): its "required" and "properties" come from the
declaration (a block merged into reports' top level: those reports'
properties of its fields), so a new field reaches the schema without an edit here. The rest
of the schema (the reports' layout, descriptions of blocks) is written by hand.

    PYTHONPATH=build/python /usr/bin/python3 python/tools/make_schema.py           # rewrite the file
    PYTHONPATH=build/python /usr/bin/python3 python/tools/make_schema.py --check   # exit 1 if it is stale

The test suite runs --check (python/tests/test_stubs.py).
"""
import json
import os
import sys

import stickslip

SCHEMA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "schema", "report.schema.json")


def field_schema(f, axis=None):
    """One field's schema, by its JSON kind and form (result_fields.hpp's FieldForm);
    a series' points are keyed by `axis` (the struct's axis field's name)."""
    if f["json"] == "series":
        if not axis:
            sys.exit(f"make_schema: the series {f['name']!r} has no axis in its struct")
        s = {"$ref": f"#/$defs/{f.get('key') or axis}_series"}  # its own point key, or its axis
    elif f["json"] == "estimate" or f["form"] == "reference":
        s = {"$ref": "#/$defs/estimate"}
    elif f["json"] == "number":
        # A number may be "inf" or null (NaN); one written only when set is never null.
        s = {"$ref": "#/$defs/number_or_inf" if f["form"] == "when_set" else "#/$defs/number_or_inf_or_null"}
    elif f["json"] == "count":
        s = {"$ref": "#/$defs/count"}
    else:
        s = {"type": f["json"]}
    unit = f" [{f['unit']}]" if f["unit"] else ""
    return {"description": f["help"] + unit, **s}


def block_schema(fields, keep, axis=None):
    """The object of the given fields (dotted names nest), keeping keep's other keys."""
    required, properties, nested = [], {}, {}
    for f in fields:
        head, dot, rest = f["name"].partition(".")
        if dot:
            nested.setdefault(head, []).append(dict(f, name=rest))
            if head not in properties:
                properties[head] = None  # its place in the order
                required.append(head)
            continue
        properties[head] = field_schema(f, axis)
        if f["form"] not in ("when_set", "optional"):
            required.append(head)
    for head, inner in nested.items():
        properties[head] = block_schema(inner, {})
        if not properties[head]["required"]:  # every field only when set: the object may be absent
            required.remove(head)
    out = {k: v for k, v in keep.items() if k not in ("type", "required", "properties", "additionalProperties")}
    out.update({"type": "object", "required": required, "properties": properties, "additionalProperties": False})
    return out


def schema_text(current):
    schema = json.loads(current)
    for declared in stickslip._core._result_fields():
        fields = [f for f in declared["fields"] if f["form"] not in ("not_in_block", "axis", "edges")]
        # A series lies along its struct's axis (points keyed by the axis' name)
        # or on its bins (FieldForm::Edges: points keyed lo and hi, "bin").
        axes = ["bin" if f["form"] == "edges" else f["name"] for f in declared["fields"] if f["form"] in ("axis", "edges")]
        axis = axes[0] if axes else None
        where = declared["schema_definition"]
        if not where:
            continue  # not in any report (Python only: Scales)
        if where.startswith("merged:"):
            # A block merged into these reports' top level: each field's property
            # (what the report requires stays the report's: it differs by method).
            for name in where[len("merged:"):].split(","):
                properties = schema["$defs"][name]["properties"]
                for f in fields:
                    properties[f["name"]] = field_schema(f, axis)
            continue
        if where not in schema["$defs"]:
            sys.exit(f"make_schema: the schema has no definition {where!r}: add an empty one")
        schema["$defs"][where] = block_schema(fields, schema["$defs"][where], axis)
    return json.dumps(schema, indent=2) + "\n"


def main(argv):
    with open(SCHEMA) as f:
        current = f.read()
    text = schema_text(current)
    if "--check" in argv:
        if text != current:
            print(f"{SCHEMA} is stale: run python/tools/make_schema.py")
            return 1
        return 0
    with open(SCHEMA, "w") as f:
        f.write(text)
    print(f"wrote {SCHEMA}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
