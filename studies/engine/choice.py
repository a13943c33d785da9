"""An evaluate that chooses between models of one mechanism by the study option ``model``
(e.g. the continuum FEM or the reduced beam model)."""
import inspect
import typing


class ModelChoice:
    """``evaluate(params, model=default, **options)``, calling ``models[model]``. Its
    signature lists ``model`` and every option any model declares (the first declaration of a
    name wins), so that a study's options are checked and typed against the whole set
    (validate.py). Picklable for worker processes: the models are module-level functions."""

    def __init__(self, default: str, **models):
        if default not in models:
            raise ValueError(f"default = {default!r} must be one of {tuple(models)}")
        self.default, self.models = default, models

    def __call__(self, params, model: str | None = None, **options) -> dict:
        model = self.default if model is None else model
        if model not in self.models:
            raise ValueError(f"model = {model!r} must be one of {tuple(self.models)}")
        return self.models[model](params, **options)

    @property
    def __signature__(self) -> inspect.Signature:
        functions = list(self.models.values())
        first = next(iter(inspect.signature(functions[0]).parameters.values()))
        options = {"model": inspect.Parameter("model", inspect.Parameter.KEYWORD_ONLY,
                                              default=self.default,
                                              annotation=typing.Literal[tuple(self.models)])}
        for function in functions:
            for p in list(inspect.signature(function).parameters.values())[1:]:
                if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY):
                    options.setdefault(p.name, p.replace(kind=p.KEYWORD_ONLY))
        return inspect.Signature([first, *options.values()])
