#!/usr/bin/env python3
"""Regenerates the malformed-pipeline corpus and its MANIFEST (run from anywhere).

Each bad case is one top-level *.json file here; helper fragments it includes live in inc/.
MANIFEST lines: `FILE  PG_ERR_CODE  substring the error message must contain`.
tests/test_pipeline_json.c loads every listed file and checks the code and the message; it also
fails if a top-level *.json file here is missing from the MANIFEST.
The generated files are committed; edit this script and rerun it to change them.
"""
import copy
import json
import os
import shutil

HERE = os.path.dirname(os.path.abspath(__file__))


def base():
    """A minimal valid pipeline; each case breaks one thing."""
    return {
        "name": "corpus",
        "parameters": {
            "debug": {"type": "bool", "default": False},
            "grid_x": {"type": "int", "default": 16, "min": 1, "max": 256},
            "exposure": {"type": "float", "default": 1.0, "min": 0.0, "max": 1000.0},
            "hdr_format": {"type": "enum", "values": ["rgba16f", "rgba32f"], "default": "rgba16f"},
        },
        "resources": [
            {"name": "hdr", "type": "image", "format": "$hdr_format"},
            {"name": "ldr", "type": "image", "format": "rgba8"},
            {"name": "lights", "type": "buffer", "stride": 32, "count": ["lights"]},
        ],
        "passes": [
            {"name": "shade", "type": "forward_naive", "reads": ["lights"], "writes": ["hdr"]},
            {"name": "display", "type": "display_tonemap", "reads": ["hdr"], "writes": ["ldr"],
             "options": {"exposure": "$exposure"}},
        ],
        "output": "ldr",
    }


cases = []    # (file, code, substring)
files = {}    # relative path -> text


def case(name, code, substring, doc=None, text=None, raw=None):
    """doc: dict dumped as JSON; text: str written as is; raw: bytes."""
    if doc is not None:
        files[name] = json.dumps(doc, indent=2) + "\n"
    elif text is not None:
        files[name] = text
    else:
        files[name] = raw
    cases.append((name, code, substring))


def mod(fn):
    d = base()
    fn(d)
    return d


def helper(name, doc):
    files[name] = json.dumps(doc, indent=2) + "\n"


good_text = json.dumps(base(), indent=2) + "\n"

# ---- JSON syntax ----
case("syntax_truncated.json", "PG_ERR_PARSE", "JSON syntax error", text=good_text[: len(good_text) // 2])
case("syntax_trailing_comma.json", "PG_ERR_PARSE", "syntax_trailing_comma.json:4:1: JSON syntax error",
     text='{\n  "name": "x",\n  "output": "ldr",\n}\n')
case("syntax_not_object.json", "PG_ERR_SCHEMA", "expected a JSON object, got an array", text="[1, 2, 3]\n")
case("syntax_string_root.json", "PG_ERR_SCHEMA", "expected a JSON object", text='"pipeline"\n')
case("syntax_empty.json", "PG_ERR_PARSE", "empty document", text="")
case("syntax_whitespace_only.json", "PG_ERR_PARSE", "empty document", text="  \n\t\n")
case("syntax_binary.json", "PG_ERR_PARSE", "JSON syntax error",
     raw=bytes((i * 73 + 41) % 256 for i in range(512)))
case("syntax_deep_nesting.json", "PG_ERR_PARSE", "JSON syntax error", text="[" * 10000)
case("syntax_deep_nesting_object.json", "PG_ERR_PARSE", "JSON syntax error",
     text='{"resources": ' + '{"a": ' * 5000 + "1" + "}" * 5000 + "}")
case("syntax_trailing_garbage.json", "PG_ERR_PARSE", "text after the JSON value",
     text=good_text + "garbage\n")
case("syntax_two_objects.json", "PG_ERR_PARSE", "text after the JSON value", text="{}\n{}\n")
case("syntax_unterminated_string.json", "PG_ERR_PARSE", "JSON syntax error",
     text='{\n  "name": "never ends\n}\n')
case("syntax_line_col.json", "PG_ERR_PARSE", "syntax_line_col.json:3:13:",
     text='{\n  "name": "x",\n  "output": ldr\n}\n')
case("syntax_single_quotes.json", "PG_ERR_PARSE", "JSON syntax error", text="{'name': 'x'}\n")
case("syntax_nul_inside.json", "PG_ERR_PARSE", "JSON syntax error", raw=b'{"name": "x"}\x00{"output": 1}')
case("syntax_duplicate_key.json", "PG_ERR_SCHEMA", "resources[1]: key 'format' appears more than once",
     text=good_text.replace('"format": "rgba8"', '"format": "rgba8", "format": "rgba16f"'))
case("syntax_huge_number.json", "PG_ERR_SCHEMA", "resources[2].stride",
     text=good_text.replace('"stride": 32', '"stride": 1e999'))

# ---- top level ----
case("top_unknown_key.json", "PG_ERR_SCHEMA", "unknown key 'outptu'",
     doc=mod(lambda d: d.update({"outptu": d.pop("output")})))
case("top_name_not_string.json", "PG_ERR_SCHEMA", "name: expected a non-empty string",
     doc=mod(lambda d: d.update({"name": 7})))
case("top_description_not_string.json", "PG_ERR_SCHEMA", "description: expected a string",
     doc=mod(lambda d: d.update({"description": ["a"]})))
case("top_resources_not_array.json", "PG_ERR_SCHEMA", "resources: expected an array",
     doc=mod(lambda d: d.update({"resources": {"hdr": {}}})))
case("top_passes_not_array.json", "PG_ERR_SCHEMA", "passes: expected an array",
     doc=mod(lambda d: d.update({"passes": "shade"})))

# ---- resources ----
case("res_not_object.json", "PG_ERR_SCHEMA", "resources[0]: expected a resource object",
     doc=mod(lambda d: d["resources"].__setitem__(0, "hdr")))
case("res_unknown_key.json", "PG_ERR_SCHEMA", "resources[1]: unknown key 'fromat'",
     doc=mod(lambda d: d["resources"][1].update({"fromat": d["resources"][1].pop("format")})))
case("res_missing_name.json", "PG_ERR_SCHEMA", "resources[1].name: missing",
     doc=mod(lambda d: d["resources"][1].pop("name")))
case("res_bad_name_chars.json", "PG_ERR_SCHEMA", "resources[1].name: expected a name matching",
     doc=mod(lambda d: d["resources"][1].update({"name": "my-ldr"})))
case("res_name_too_long.json", "PG_ERR_SCHEMA", "resources[1].name: expected a name",
     doc=mod(lambda d: d["resources"][1].update({"name": "l" * 64})))
case("res_missing_type.json", "PG_ERR_SCHEMA", "resources[0].type: missing",
     doc=mod(lambda d: d["resources"][0].pop("type")))
case("res_bad_type.json", "PG_ERR_SCHEMA", "resources[0].type: expected \"image\" or \"buffer\"",
     doc=mod(lambda d: d["resources"][0].update({"type": "texture"})))
case("res_missing_format.json", "PG_ERR_SCHEMA", "resources[1].format: missing",
     doc=mod(lambda d: d["resources"][1].pop("format")))
case("res_unknown_format.json", "PG_ERR_FORMAT", "unknown format 'rgb8' (valid: rgba8",
     doc=mod(lambda d: d["resources"][1].update({"format": "rgb8"})))
case("res_format_undefined.json", "PG_ERR_FORMAT", "unknown format 'undefined'",
     doc=mod(lambda d: d["resources"][1].update({"format": "undefined"})))
case("res_format_not_string.json", "PG_ERR_SCHEMA", "resources[1].format: expected a format name",
     doc=mod(lambda d: d["resources"][1].update({"format": 37})))
case("res_scale_zero.json", "PG_ERR_SCHEMA", "resources[1].scale: expected a number or [x, y]",
     doc=mod(lambda d: d["resources"][1].update({"scale": 0})))
case("res_scale_too_big.json", "PG_ERR_SCHEMA", "resources[1].scale",
     doc=mod(lambda d: d["resources"][1].update({"scale": [1.0, 17]})))
case("res_scale_three.json", "PG_ERR_SCHEMA", "resources[1].scale",
     doc=mod(lambda d: d["resources"][1].update({"scale": [1, 1, 1]})))
case("res_scale_string.json", "PG_ERR_SCHEMA", "resources[1].scale",
     doc=mod(lambda d: d["resources"][1].update({"scale": "half"})))
case("res_scale_and_extent.json", "PG_ERR_SCHEMA", "not both",
     doc=mod(lambda d: d["resources"][1].update({"scale": 0.5, "extent": [64, 64]})))
case("res_extent_zero.json", "PG_ERR_SCHEMA", "resources[1].extent: expected [width, height]",
     doc=mod(lambda d: d["resources"][1].update({"extent": [0, 64]})))
case("res_extent_too_big.json", "PG_ERR_SCHEMA", "resources[1].extent",
     doc=mod(lambda d: d["resources"][1].update({"extent": [64, 16385]})))
case("res_extent_fraction.json", "PG_ERR_SCHEMA", "resources[1].extent",
     doc=mod(lambda d: d["resources"][1].update({"extent": [64.5, 64]})))
case("res_extent_not_array.json", "PG_ERR_SCHEMA", "resources[1].extent",
     doc=mod(lambda d: d["resources"][1].update({"extent": 64})))
case("res_extent_one_element.json", "PG_ERR_SCHEMA", "resources[1].extent",
     doc=mod(lambda d: d["resources"][1].update({"extent": [64]})))
case("res_bad_lifetime.json", "PG_ERR_SCHEMA", "resources[1].lifetime: expected \"transient\"",
     doc=mod(lambda d: d["resources"][1].update({"lifetime": "forever"})))
case("res_description_not_string.json", "PG_ERR_SCHEMA", "resources[0].description",
     doc=mod(lambda d: d["resources"][0].update({"description": 1})))
case("res_duplicate.json", "PG_ERR_SCHEMA", "resource 'hdr' is declared twice: first at",
     doc=mod(lambda d: d["resources"].append({"name": "hdr", "type": "image", "format": "rgba8"})))
case("image_with_stride.json", "PG_ERR_SCHEMA", "resources[1].stride: 'stride' is only for buffer",
     doc=mod(lambda d: d["resources"][1].update({"stride": 4})))
case("image_with_count.json", "PG_ERR_SCHEMA", "resources[1].count: 'count' is only for buffer",
     doc=mod(lambda d: d["resources"][1].update({"count": [4]})))
case("buf_with_format.json", "PG_ERR_SCHEMA", "resources[2].format: 'format' is only for image",
     doc=mod(lambda d: d["resources"][2].update({"format": "r32f"})))
case("buf_with_scale.json", "PG_ERR_SCHEMA", "resources[2].scale: 'scale' is only for image",
     doc=mod(lambda d: d["resources"][2].update({"scale": 1})))
case("buf_with_extent.json", "PG_ERR_SCHEMA", "resources[2].extent: 'extent' is only for image",
     doc=mod(lambda d: d["resources"][2].update({"extent": [4, 4]})))
case("buf_missing_stride.json", "PG_ERR_SCHEMA", "resources[2].stride: missing",
     doc=mod(lambda d: d["resources"][2].pop("stride")))
case("buf_stride_zero.json", "PG_ERR_SCHEMA", "resources[2].stride: expected an integer in 1..65536",
     doc=mod(lambda d: d["resources"][2].update({"stride": 0})))
case("buf_stride_too_big.json", "PG_ERR_SCHEMA", "resources[2].stride",
     doc=mod(lambda d: d["resources"][2].update({"stride": 65537})))
case("buf_stride_fraction.json", "PG_ERR_SCHEMA", "got 4.5",
     doc=mod(lambda d: d["resources"][2].update({"stride": 4.5})))
case("buf_stride_string.json", "PG_ERR_SCHEMA", "resources[2].stride",
     doc=mod(lambda d: d["resources"][2].update({"stride": "32"})))
case("buf_count_empty.json", "PG_ERR_SCHEMA", "resources[2].count: expected a non-empty array",
     doc=mod(lambda d: d["resources"][2].update({"count": []})))
case("buf_count_not_array.json", "PG_ERR_SCHEMA", "resources[2].count: expected a non-empty array",
     doc=mod(lambda d: d["resources"][2].update({"count": 16})))
case("buf_count_negative.json", "PG_ERR_SCHEMA", "resources[2].count[1]: expected a non-negative integer",
     doc=mod(lambda d: d["resources"][2].update({"count": ["lights", -1]})))
case("buf_count_fraction.json", "PG_ERR_SCHEMA", "resources[2].count[0]",
     doc=mod(lambda d: d["resources"][2].update({"count": [2.5]})))
case("buf_count_unknown_term.json", "PG_ERR_SCHEMA", "resources[2].count[0]",
     doc=mod(lambda d: d["resources"][2].update({"count": ["Texels!"]})))
case("buf_count_too_many_terms.json", "PG_ERR_LIMIT", "resources[2].count: 5 terms",
     doc=mod(lambda d: d["resources"][2].update({"count": [1, 2, 3, 4, 5]})))
case("buf_grow_not_bool.json", "PG_ERR_SCHEMA", "resources[2].grow: expected true or false, got",
     doc=mod(lambda d: d["resources"][2].update({"grow": 1})))
case("img_with_grow.json", "PG_ERR_SCHEMA", "resources[0].grow: 'grow' is only for buffer",
     doc=mod(lambda d: d["resources"][0].update({"grow": True})))

# ---- passes ----
case("pass_not_object.json", "PG_ERR_SCHEMA", "passes[1]: expected a pass object",
     doc=mod(lambda d: d["passes"].__setitem__(1, ["display"])))
case("pass_unknown_key.json", "PG_ERR_SCHEMA", "passes[1]: unknown key 'reed'",
     doc=mod(lambda d: d["passes"][1].update({"reed": d["passes"][1].pop("reads")})))
case("pass_missing_name.json", "PG_ERR_SCHEMA", "passes[0].name: missing",
     doc=mod(lambda d: d["passes"][0].pop("name")))
case("pass_missing_type.json", "PG_ERR_SCHEMA", "passes[0].type: missing",
     doc=mod(lambda d: d["passes"][0].pop("type")))
case("pass_type_not_string.json", "PG_ERR_SCHEMA", "passes[0].type: expected a name",
     doc=mod(lambda d: d["passes"][0].update({"type": {"id": 1}})))
case("pass_reads_not_array.json", "PG_ERR_SCHEMA", "passes[1].reads: expected an array of names",
     doc=mod(lambda d: d["passes"][1].update({"reads": "hdr"})))
case("pass_read_not_string.json", "PG_ERR_SCHEMA", "passes[1].reads[0]: expected a name",
     doc=mod(lambda d: d["passes"][1].update({"reads": [1]})))
case("unknown_resource_read.json", "PG_ERR_UNKNOWN_RESOURCE", "passes[1].reads[0]: unknown resource 'hdrr'",
     doc=mod(lambda d: d["passes"][1].update({"reads": ["hdrr"]})))
case("unknown_resource_write.json", "PG_ERR_UNKNOWN_RESOURCE", "passes[0].writes[0]",
     doc=mod(lambda d: d["passes"][0].update({"writes": ["color"]})))
case("pass_too_many_reads.json", "PG_ERR_LIMIT", "passes[1].reads: 13 entries",
     doc=mod(lambda d: d["passes"][1].update({"reads": ["hdr"] * 13})))
case("pass_after_unknown.json", "PG_ERR_SCHEMA", "passes[1].after[0]: unknown pass 'shading'",
     doc=mod(lambda d: d["passes"][1].update({"after": ["shading"]})))
case("pass_too_many_after.json", "PG_ERR_LIMIT", "passes[1].after: 9 entries",
     doc=mod(lambda d: d["passes"][1].update({"after": ["shade"] * 9})))
case("pass_side_effects_not_bool.json", "PG_ERR_SCHEMA", "passes[0].side_effects: expected true or false",
     doc=mod(lambda d: d["passes"][0].update({"side_effects": "yes"})))
case("pass_options_not_object.json", "PG_ERR_SCHEMA", "passes[1].options: expected an object",
     doc=mod(lambda d: d["passes"][1].update({"options": ["exposure", 1]})))
case("pass_duplicate.json", "PG_ERR_SCHEMA", "pass 'shade' is declared twice",
     doc=mod(lambda d: d["passes"].append({"name": "shade", "type": "x", "writes": ["ldr"]})))

# ---- parameters ----
case("param_default_out_of_range.json", "PG_ERR_PARAM", "parameters.grid_x.default: 300 is out of range [1, 256]",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"default": 300})))
case("param_enum_default_not_in_values.json", "PG_ERR_PARAM", "parameters.hdr_format.default",
     doc=mod(lambda d: d["parameters"]["hdr_format"].update({"default": "rgba8"})))
case("param_unknown_type.json", "PG_ERR_PARAM", "parameters.exposure.type: unknown parameter type 'double'",
     doc=mod(lambda d: d["parameters"]["exposure"].update({"type": "double"})))
case("param_missing_type.json", "PG_ERR_PARAM", "parameters.exposure.type: missing",
     doc=mod(lambda d: d["parameters"]["exposure"].pop("type")))
case("param_enum_empty_values.json", "PG_ERR_PARAM", "parameters.hdr_format.values: an enum needs a non-empty array",
     doc=mod(lambda d: d["parameters"]["hdr_format"].update({"values": []})))
case("param_enum_missing_values.json", "PG_ERR_PARAM", "parameters.hdr_format.values",
     doc=mod(lambda d: d["parameters"]["hdr_format"].pop("values")))
case("param_enum_value_not_string.json", "PG_ERR_PARAM", "parameters.hdr_format.values[1]",
     doc=mod(lambda d: d["parameters"]["hdr_format"].update({"values": ["rgba16f", 32]})))
case("param_enum_dup_value.json", "PG_ERR_PARAM", "parameters.hdr_format.values[1]: 'rgba16f' is listed twice",
     doc=mod(lambda d: d["parameters"]["hdr_format"].update({"values": ["rgba16f", "rgba16f"]})))
case("param_too_many_values.json", "PG_ERR_LIMIT", "parameters.hdr_format.values: 13 values",
     doc=mod(lambda d: d["parameters"]["hdr_format"].update({"values": ["rgba16f"] + ["v%d" % i for i in range(12)]})))
case("param_missing_default.json", "PG_ERR_PARAM", "parameters.grid_x.default: missing",
     doc=mod(lambda d: d["parameters"]["grid_x"].pop("default")))
case("param_min_gt_max.json", "PG_ERR_PARAM", "parameters.grid_x.max: 1 is less than min 8",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"min": 8, "max": 1})))
case("param_int_default_2p53.json", "PG_ERR_PARAM",
     "parameters.grid_x.default: expected an integer of magnitude below 2^53",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"default": 9007199254740993, "min": 1, "max": 9007199254740991})))
case("param_int_default_fraction.json", "PG_ERR_PARAM", "parameters.grid_x.default: expected an integer",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"default": 1.5})))
case("param_bool_default_string.json", "PG_ERR_PARAM", "parameters.debug.default: expected true or false",
     doc=mod(lambda d: d["parameters"]["debug"].update({"default": "false"})))
case("param_bool_with_min.json", "PG_ERR_PARAM", "parameters.debug.min: only int and float",
     doc=mod(lambda d: d["parameters"]["debug"].update({"min": 0})))
case("param_values_on_float.json", "PG_ERR_PARAM", "parameters.exposure.values: only enum and int parameters",
     doc=mod(lambda d: d["parameters"]["exposure"].update({"values": [1.0]})))
case("param_int_value_string.json", "PG_ERR_PARAM",
     "parameters.grid_x.values[0]: expected an integer in [1, 256], got \"1\"",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"values": ["1"]})))
case("param_int_value_out_of_range.json", "PG_ERR_PARAM",
     "parameters.grid_x.values[1]: expected an integer in [1, 256], got 512",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"values": [16, 512]})))
case("param_int_dup_value.json", "PG_ERR_PARAM", "parameters.grid_x.values[1]: 16 is listed twice",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"values": [16, 16]})))
case("param_int_default_not_in_values.json", "PG_ERR_PARAM",
     "parameters.grid_x.default: 16 is not one of the values (8, 32)",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"values": [8, 32]})))
case("plugins_too_many.json", "PG_ERR_LIMIT", "plugins: 5 plug-ins, at most 4",
     doc=mod(lambda d: d.update({"plugins": ["a.so", "b.so", "c.so", "d.so", "e.so"]})))
case("plugins_not_array.json", "PG_ERR_SCHEMA", "plugins: expected an array of at most 4 shared-library paths, got",
     doc=mod(lambda d: d.update({"plugins": "a.so"})))
case("param_unknown_key.json", "PG_ERR_SCHEMA", "parameters.grid_x: unknown key 'deafult'",
     doc=mod(lambda d: d["parameters"]["grid_x"].update({"deafult": 3})))
case("param_bad_name.json", "PG_ERR_PARAM", "parameters.grid-y: parameter names must match",
     doc=mod(lambda d: d["parameters"].update({"grid-y": {"type": "int", "default": 1}})))
case("param_not_object.json", "PG_ERR_PARAM", "parameters.gamma: expected a declaration object",
     doc=mod(lambda d: d["parameters"].update({"gamma": 2.2})))
case("parameters_not_object.json", "PG_ERR_SCHEMA", "parameters: expected an object",
     doc=mod(lambda d: d.update({"parameters": [d["parameters"]]})))
case("param_duplicate_key.json", "PG_ERR_SCHEMA", "parameters: key 'debug' appears more than once",
     text=good_text.replace('"parameters": {', '"parameters": {\n    "debug": {"type": "bool", "default": true},', 1))

# ---- $param references ----
case("ref_unknown_param.json", "PG_ERR_PARAM", "passes[1].options.exposure: unknown parameter '$exposur'",
     doc=mod(lambda d: d["passes"][1]["options"].update({"exposure": "$exposur"})))
case("ref_unknown_in_array.json", "PG_ERR_PARAM", "resources[2].count[1]: unknown parameter '$nope'",
     doc=mod(lambda d: d["resources"][2].update({"count": ["lights", "$nope"]})))
case("ref_unknown_nested.json", "PG_ERR_PARAM", "passes[0].options.grid.size[2]: unknown parameter '$grid_z'",
     doc=mod(lambda d: d["passes"][0].update({"options": {"grid": {"size": ["$grid_x", 9, "$grid_z"]}}})))
case("ref_wrong_type.json", "PG_ERR_SCHEMA", "resources[0].format: expected a format name, got 16",
     doc=mod(lambda d: d["resources"][0].update({"format": "$grid_x"})))

# ---- when ----
case("when_malformed_op.json", "PG_ERR_SCHEMA", "passes[1].when: malformed condition",
     doc=mod(lambda d: d["passes"][1].update({"when": "$debug = true"})))
case("when_no_dollar.json", "PG_ERR_SCHEMA", "passes[1].when: malformed condition",
     doc=mod(lambda d: d["passes"][1].update({"when": "debug == true"})))
case("when_extra_tokens.json", "PG_ERR_SCHEMA", "resources[1].when: malformed condition",
     doc=mod(lambda d: d["resources"][1].update({"when": "$debug == true && $grid_x == 4"})))
case("when_bare_param.json", "PG_ERR_SCHEMA", "passes[0].when: malformed condition",
     doc=mod(lambda d: d["passes"][0].update({"when": "$debug"})))
case("when_not_string.json", "PG_ERR_SCHEMA", "passes[1].when: expected \"$param == value\"",
     doc=mod(lambda d: d["passes"][1].update({"when": True})))
case("when_unknown_param.json", "PG_ERR_PARAM", "passes[1].when: unknown parameter '$dbg'",
     doc=mod(lambda d: d["passes"][1].update({"when": "$dbg == true"})))
case("when_bad_bool_value.json", "PG_ERR_SCHEMA", "cannot compare bool parameter 'debug'",
     doc=mod(lambda d: d["passes"][1].update({"when": "$debug == yes"})))
case("when_bad_enum_value.json", "PG_ERR_SCHEMA", "'rgba8' is not one of: rgba16f, rgba32f",
     doc=mod(lambda d: d["passes"][1].update({"when": "$hdr_format != rgba8"})))
case("when_bad_int_value.json", "PG_ERR_SCHEMA", "cannot compare int parameter 'grid_x'",
     doc=mod(lambda d: d["passes"][1].update({"when": "$grid_x == 4.5"})))
case("omitted_resource_read.json", "PG_ERR_UNKNOWN_RESOURCE",
     "passes[1].reads[1]: resource 'debug_view' (omitted_resource_read.json: resources[3]) is omitted: when: $debug == true (debug is 'false')",
     doc=mod(lambda d: (d["resources"].append({"name": "debug_view", "type": "image", "format": "rgba8",
                                                "when": "$debug == true"}),
                         d["passes"][1]["reads"].append("debug_view"))))
case("omitted_resource_write.json", "PG_ERR_UNKNOWN_RESOURCE", "passes[0].writes[0]: resource 'hdr'",
     doc=mod(lambda d: d["resources"][0].update({"when": "$hdr_format == rgba32f"})))

# ---- outputs ----
case("output_missing.json", "PG_ERR_NO_OUTPUT", "output: missing", doc=mod(lambda d: d.pop("output")))
case("output_is_buffer.json", "PG_ERR_NO_OUTPUT", "output: 'lights' is a buffer",
     doc=mod(lambda d: d.update({"output": "lights"})))
case("output_unknown.json", "PG_ERR_NO_OUTPUT", "output: unknown resource 'ldr2'",
     doc=mod(lambda d: d.update({"output": "ldr2"})))
case("output_omitted.json", "PG_ERR_NO_OUTPUT", "output: resource 'ldr' is omitted: when: $debug != false",
     doc=mod(lambda d: (d["resources"][1].update({"when": "$debug != false"}),
                         d["passes"][1].update({"when": "$debug == true"}))))
case("output_not_string.json", "PG_ERR_SCHEMA", "output: expected an image resource name",
     doc=mod(lambda d: d.update({"output": ["ldr"]})))
case("hdr_output_unknown.json", "PG_ERR_NO_OUTPUT", "hdr_output: unknown resource 'hdr2'",
     doc=mod(lambda d: d.update({"hdr_output": "hdr2"})))
case("hdr_output_is_buffer.json", "PG_ERR_NO_OUTPUT", "hdr_output: 'lights' is a buffer",
     doc=mod(lambda d: d.update({"hdr_output": "lights"})))

# ---- includes ----
helper("inc/cycle_a.json", {"include": ["cycle_b.json"]})
helper("inc/cycle_b.json", {"include": ["cycle_a.json"]})
for i in range(1, 18):
    helper("inc/deep/d%02d.json" % i, {"include": ["d%02d.json" % (i + 1)]} if i < 17 else {})
helper("inc/frag_with_output.json", {"resources": [], "output": "ldr"})
helper("inc/frag_with_name.json", {"name": "fragment"})
helper("inc/frag_hdr.json", {"resources": [{"name": "hdr", "type": "image", "format": "rgba16f"}]})
helper("inc/frag_shade.json", {"passes": [{"name": "shade", "type": "x", "writes": ["hdr"]}]})
helper("inc/frag_param_exposure.json",
       {"parameters": {"exposure": {"type": "float", "default": 2.0, "min": 0.0, "max": 1000.0}}})
files["inc/broken.json"] = '{\n  "resources": [\n    {"name": "x",, "type": "image"}\n  ]\n}\n'
helper("inc/frag_bad_format.json", {"resources": [{"name": "tmp", "type": "image", "format": "rgba9"}]})
helper("inc/frag_bad_read.json", {"passes": [{"name": "extra", "type": "x", "reads": ["nothing"]}]})
helper("inc/shared_res.json", {"resources": [{"name": "shared", "type": "image", "format": "r32f"}]})
helper("inc/diamond_l.json", {"include": ["shared_res.json"]})
helper("inc/diamond_r.json", {"include": ["shared_res.json"]})
helper("inc/many_passes.json",
       {"passes": [{"name": "frag_pass%d" % i, "type": "x", "writes": ["hdr"]} for i in range(40)]})
helper("inc/frag_nested_include_missing.json", {"include": ["no_such_fragment.json"]})

case("include_missing.json", "PG_ERR_INCLUDE", "include[0]: cannot open 'inc/does_not_exist.json'",
     doc=mod(lambda d: d.update({"include": ["inc/does_not_exist.json"]})))
case("include_nested_missing.json", "PG_ERR_INCLUDE",
     "inc/frag_nested_include_missing.json: include[0]: cannot open 'inc/no_such_fragment.json'",
     doc=mod(lambda d: d.update({"include": ["inc/frag_nested_include_missing.json"]})))
case("include_cycle.json", "PG_ERR_INCLUDE",
     "include cycle: include_cycle.json -> inc/cycle_a.json -> inc/cycle_b.json -> inc/cycle_a.json",
     doc=mod(lambda d: d.update({"include": ["inc/cycle_a.json"]})))
case("include_self.json", "PG_ERR_INCLUDE", "include[0]: include cycle",
     doc=mod(lambda d: d.update({"include": ["include_self.json"]})))
case("include_too_deep.json", "PG_ERR_INCLUDE", "includes nested deeper than 16 levels",
     doc=mod(lambda d: d.update({"include": ["inc/deep/d01.json"]})))
case("include_not_array.json", "PG_ERR_SCHEMA", "include: expected an array of relative paths",
     doc=mod(lambda d: d.update({"include": "inc/frag_hdr.json"})))
case("include_entry_not_string.json", "PG_ERR_SCHEMA", "include[1]: expected a file path",
     doc=mod(lambda d: d.update({"include": ["inc/shared_res.json", 3]})))
case("include_directory.json", "PG_ERR_INCLUDE", "include[0]: 'inc' is a directory, not a regular file",
     doc=mod(lambda d: d.update({"include": ["inc"]})))
case("include_fragment_has_output.json", "PG_ERR_SCHEMA",
     "inc/frag_with_output.json: (top level): unknown key 'output' in an included fragment",
     doc=mod(lambda d: d.update({"include": ["inc/frag_with_output.json"]})))
case("include_fragment_has_name.json", "PG_ERR_SCHEMA", "inc/frag_with_name.json: (top level): unknown key 'name'",
     doc=mod(lambda d: d.update({"include": ["inc/frag_with_name.json"]})))
case("include_duplicate_resource.json", "PG_ERR_SCHEMA",
     "include_duplicate_resource.json: resources[0].name: resource 'hdr' is declared twice: first at inc/frag_hdr.json: resources[0]",
     doc=mod(lambda d: d.update({"include": ["inc/frag_hdr.json"]})))
case("include_duplicate_pass.json", "PG_ERR_SCHEMA", "pass 'shade' is declared twice: first at inc/frag_shade.json: passes[0]",
     doc=mod(lambda d: d.update({"include": ["inc/frag_shade.json"]})))
case("include_param_conflict.json", "PG_ERR_PARAM",
     "parameters.exposure: parameter 'exposure' is already declared differently at inc/frag_param_exposure.json",
     doc=mod(lambda d: d.update({"include": ["inc/frag_param_exposure.json"]})))
case("include_syntax_error.json", "PG_ERR_PARSE", "inc/broken.json:3:18: JSON syntax error",
     doc=mod(lambda d: d.update({"include": ["inc/broken.json"]})))
case("include_bad_format_in_fragment.json", "PG_ERR_FORMAT", "inc/frag_bad_format.json: resources[0].format: unknown format 'rgba9'",
     doc=mod(lambda d: d.update({"include": ["inc/frag_bad_format.json"]})))
case("include_bad_read_in_fragment.json", "PG_ERR_UNKNOWN_RESOURCE", "inc/frag_bad_read.json: passes[0].reads[0]: unknown resource 'nothing'",
     doc=mod(lambda d: d.update({"include": ["inc/frag_bad_read.json"]})))
case("include_diamond_resource.json", "PG_ERR_SCHEMA", "inc/shared_res.json: resources[0].name: resource 'shared' is declared twice: first at inc/shared_res.json: resources[0] (the same file is included more than once)",
     doc=mod(lambda d: d.update({"include": ["inc/diamond_l.json", "inc/diamond_r.json"]})))

# ---- limits ----
case("limit_passes.json", "PG_ERR_LIMIT", "passes[64]: more than 64 passes",
     doc=mod(lambda d: d["passes"].extend({"name": "p%d" % i, "type": "x", "writes": ["hdr"]} for i in range(63))))
case("limit_passes_across_include.json", "PG_ERR_LIMIT", "passes[24]: more than 64 passes",
     doc=mod(lambda d: (d.update({"include": ["inc/many_passes.json"]}),
                         d["passes"].extend({"name": "p%d" % i, "type": "x", "writes": ["hdr"]} for i in range(23)))))
case("limit_resources.json", "PG_ERR_LIMIT", "resources[96]: more than 96 resources",
     doc=mod(lambda d: d["resources"].extend({"name": "r%d" % i, "type": "image", "format": "rgba8"} for i in range(94))))
case("limit_params.json", "PG_ERR_LIMIT", "parameters.p44: more than 48 parameters",
     doc=mod(lambda d: d["parameters"].update({"p%d" % i: {"type": "int", "default": i} for i in range(45)})))
case("limit_writes.json", "PG_ERR_LIMIT", "passes[0].writes: 13 entries, the limit is 12",
     doc=mod(lambda d: d["passes"][0].update({"writes": ["hdr"] * 13})))


def main():
    for sub in ("inc",):
        shutil.rmtree(os.path.join(HERE, sub), ignore_errors=True)
    for name in os.listdir(HERE):
        if name.endswith(".json"):
            os.remove(os.path.join(HERE, name))
    for name, content in files.items():
        path = os.path.join(HERE, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        mode = "wb" if isinstance(content, bytes) else "w"
        with open(path, mode) as f:
            f.write(content)
    names = [c[0] for c in cases]
    assert len(names) == len(set(names)), "duplicate case names"
    width = max(len(n) for n in names)
    with open(os.path.join(HERE, "MANIFEST"), "w") as f:
        f.write("# FILE  PG_ERR_CODE  substring the message must contain (rest of the line)\n")
        f.write("# Generated by gen_corpus.py; the message must also name FILE (or the fragment in the substring).\n")
        for n, code, sub in cases:
            f.write("%-*s  %-24s %s\n" % (width, n, code, sub))
    print("%d cases" % len(cases))


if __name__ == "__main__":
    main()
