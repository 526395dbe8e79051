"""Check a JSONL file of annotated scene descriptions: python3 check.py FILE [FILE ...]"""
import json
import re
import sys

TAGS = {"OBJ", "ANY", "TOTAL", "REF", "DROP", "SRC", "TGT", "PICK", "NEAR", "ON", "IN", "POS", "POS_NEXT",
        "POS_ALL", "LIGHT", "CAM"}
REL = {"pick_up": "PICK", "move_near": "NEAR", "put_on": "ON", "put_in": "IN"}
NAMES = set("""coke can|pepsi can|7up can|sprite can|fanta can|redbull can|apple|orange|sponge|blue plastic bottle|
carrot|plate|spoon|towel|green cube|yellow cube|eggplant|basket|coffee can|cracker box|sugar box|tomato soup can|
mustard bottle|tuna can|pudding box|gelatin box|spam can|banana|strawberry|red apple|lemon|peach|pear|navel orange|
plum|pitcher|bleach bottle|windex bottle|bowl|mug|scrub sponge|skillet lid|red plate|fork|red spoon|knife|spatula|
power drill|wooden block|scissors|padlock|marker|wrench|phillips screwdriver|flat screwdriver|hammer|medium clamp|
large clamp|extra large clamp|soccer ball|softball|baseball|tennis ball|racquetball|golf ball|foam brick|dice|
marble|orange cup|light blue cup|green cup|yellow cup|red cup|purple cup|large orange cup|large blue cup|
large green cup|large yellow cup|blue wooden cube|peg board|toy airplane|green lego brick|purple lego brick|
pink lego brick|yellow lego brick|blue lego brick|small yellow lego brick|orange lego board|rubik's cube""".replace("\n", "").split("|"))
MARK = re.compile(r"\[\[([^\[\]|]+)\|([A-Z_]+)\]\]")


def check_row(row):
    errs = []
    ann = row.get("annotated")
    if not isinstance(ann, str) or not ann.strip():
        return ["no annotated text"]
    tags = []
    for m in MARK.finditer(ann):
        if m.group(2) not in TAGS:
            errs.append(f"unknown tag {m.group(2)!r}")
        tags.append(m.group(2))
    rest = MARK.sub(" ", ann)
    if "[[" in rest or "]]" in rest or re.search(r"\|[A-Z_]+\]", rest):
        errs.append("broken markup (nested, unclosed or missing |TAG)")
    exp = row.get("expected")
    if not isinstance(exp, dict):
        return errs + ["no expected"]
    for k in ("n_objects", "required_objects", "task", "lighting", "camera"):
        if k not in exp:
            errs.append(f"expected lacks {k}")
    task = exp.get("task") or {}
    ttype = task.get("type")
    if ttype not in REL:
        errs.append(f"task type {ttype!r}")
    else:
        rels = [t for t in tags if t in ("PICK", "NEAR", "ON", "IN")]
        if not rels:
            errs.append("no task relation tag (PICK/NEAR/ON/IN)")
        elif rels[-1] != REL[ttype] and not (ttype != "pick_up" and REL[ttype] in rels):
            errs.append(f"relation tags {rels} do not say {ttype}")
        if "SRC" not in tags:
            errs.append("no SRC")
        if ttype != "pick_up" and "TGT" not in tags:
            errs.append("no TGT")
        if ttype == "pick_up" and "TGT" in tags:
            errs.append("TGT in a pick_up")
    unavailable = set(exp.get("unavailable", []))
    for n in exp.get("required_objects", []):
        if n not in NAMES:
            errs.append(f"required object {n!r} is not a catalog name")
    for key in ("object", "target"):
        n = task.get(key)
        if n is not None and n not in NAMES and n not in unavailable:
            errs.append(f"task {key} {n!r} is neither a catalog name nor listed unavailable")
    if not isinstance(exp.get("n_objects"), int):
        errs.append("n_objects must be an int")
    light = exp.get("lighting")
    if light is not None and (light.get("direction") not in ("brighter", "darker")):
        errs.append("lighting direction must be brighter or darker")
    if light is not None and "LIGHT" not in tags:
        errs.append("a lighting change but no LIGHT tag")
    if light is None and "LIGHT" in tags:
        errs.append("LIGHT tagged but lighting is null")
    cam = exp.get("camera")
    if cam is not None and "CAM" not in tags:
        errs.append("a camera change but no CAM tag")
    if cam is None and "CAM" in tags:
        errs.append("CAM tagged but camera is null")
    if cam is not None:
        t = cam.get("translate_cm")
        if t is not None and (not isinstance(t, list) or len(t) != 3):
            errs.append("translate_cm must be [x, y, z] or null")
        r = cam.get("rotate_deg")
        if r is not None and (not isinstance(r, dict) or set(r) - {"yaw", "pitch", "roll"}):
            errs.append("rotate_deg keys are yaw / pitch / roll")
    for p in exp.get("positions", []):
        w = p.get("where", "")
        if not (w in ("left", "right", "front", "back", "center") or (w.startswith("near:") and w[5:] in NAMES)):
            errs.append(f"position {w!r}")
    return errs


def main():
    bad = 0
    n = 0
    ids = set()
    for path in sys.argv[1:]:
        for i, line in enumerate(open(path, encoding="utf-8"), 1):
            if not line.strip():
                continue
            n += 1
            try:
                row = json.loads(line)
            except json.JSONDecodeError as e:
                print(f"{path}:{i}: not JSON: {e}")
                bad += 1
                continue
            if row.get("id") in ids:
                print(f"{path}:{i}: duplicate id {row.get('id')}")
            ids.add(row.get("id"))
            errs = check_row(row)
            if errs:
                bad += 1
                print(f"{path}:{i} {row.get('id')}: " + "; ".join(errs))
    print(f"{n} rows, {bad} with problems")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
