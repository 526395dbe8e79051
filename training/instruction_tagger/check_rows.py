"""Check a JSONL file of annotated instructions: python3 check.py FILE [FILE ...]"""
import json, re, sys
TAGS = {"OBJ", "REF", "DROP", "SRC", "TGT", "PICK", "NEAR", "ON", "IN", "NEG", "EXTRA"}
REL = {"pick_up": "PICK", "move_near": "NEAR", "put_on": "ON", "put_in": "IN"}
MARK = re.compile(r"\[\[([^\[\]|]+)\|([A-Z_]+)\]\]")
SAME = {"object_synonym","verb_synonym","question","polite","casual","reorder","context","decomposed","end_state","need","cleft","passive","learner_english","dictated"}
DIFF = {"similar_object_swap","other_object_swap","role_swap","task_change","relation_change","destination_change","negation","extra_step","extra_object","dropped_target","underspecified","qualifier_change"}
def check(row):
    errs = []
    ann = row.get("annotated")
    if not isinstance(ann, str) or not ann.strip():
        return ["no annotated text"]
    tags = [m.group(2) for m in MARK.finditer(ann)]
    errs += [f"unknown tag {t}" for t in tags if t not in TAGS]
    rest = MARK.sub(" ", ann)
    if "[[" in rest or "]]" in rest or re.search(r"\|[A-Z_]+\]", rest):
        errs.append("broken markup")
    if row.get("role") not in ("original", "candidate"):
        errs.append("role must be original or candidate")
    if row.get("role") == "candidate":
        if row.get("label") not in ("same", "different"):
            errs.append("label must be same or different")
        cat = row.get("category")
        if (row.get("label") == "same" and cat not in SAME) or (row.get("label") == "different" and cat not in DIFF):
            errs.append(f"category {cat!r} does not fit label {row.get('label')!r}")
    f = row.get("frame")
    if not isinstance(f, dict):
        return errs + ["no frame"]
    task = f.get("task")
    if task in REL:
        rels = [t for t in tags if t in ("PICK", "NEAR", "ON", "IN")]
        if not rels:
            errs.append("no relation tag")
        elif REL[task] not in rels:
            errs.append(f"relation tags {rels} do not say {task}")
        if "SRC" not in tags and f.get("object"):
            errs.append("object named but no SRC")
        if task != "pick_up" and f.get("target") and "TGT" not in tags:
            errs.append("target named but no TGT")
    if bool(f.get("negated")) != ("NEG" in tags):
        errs.append("negated must match a NEG tag")
    if bool(f.get("extra")) != ("EXTRA" in tags):
        errs.append("extra must match an EXTRA tag")
    return errs
bad = n = 0
for path in sys.argv[1:]:
    for i, line in enumerate(open(path, encoding="utf-8"), 1):
        if not line.strip():
            continue
        n += 1
        try:
            row = json.loads(line)
        except json.JSONDecodeError as e:
            print(f"{path}:{i}: not JSON: {e}"); bad += 1; continue
        errs = check(row)
        if errs:
            bad += 1
            print(f"{path}:{i} {row.get('id')}: " + "; ".join(errs))
print(f"{n} rows, {bad} with problems")
sys.exit(1 if bad else 0)
