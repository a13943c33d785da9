"""Whether a model file describes a spatial mechanism (3-D bodies), from its raw tables:
imports nothing, so the model-file reader may ask before it reads."""


def is_spatial(raw: dict) -> bool:
    """Whether a model file's bodies are 3-D: a box with three coordinates per corner, a
    cylinder or a prism."""
    for body in raw.get("body", []) if isinstance(raw.get("body"), list) else []:
        if not isinstance(body, dict):
            continue
        if "cylinder" in body or "prism" in body:
            return True
        box = body.get("box")
        while isinstance(box, list) and box and isinstance(box[0], list):
            box = box[0]
        if isinstance(box, list) and len(box) == 3:
            return True
    return False
