"""Whether a model file describes a spatial mechanism (3-D bodies), from its raw tables:
imports nothing, so the model-file reader may ask before it reads."""


def is_spatial(raw: dict) -> bool:
    """Whether a model file's bodies are 3-D: a cylinder or a prism, or boxes whose corners
    all have three coordinates (a file that mixes two and three is planar, and its planar
    reading names the corner that is not a pair)."""
    corners = []
    for body in raw.get("body", []) if isinstance(raw.get("body"), list) else []:
        if not isinstance(body, dict):
            continue
        if "cylinder" in body or "prism" in body:
            return True
        box = body.get("box")
        boxes = box if isinstance(box, list) and box and isinstance(box[0], list) and box[0] \
            and isinstance(box[0][0], list) else [box]
        corners += [len(c) for b in boxes if isinstance(b, list) for c in b if isinstance(c, list)]
    return bool(corners) and all(n == 3 for n in corners)
