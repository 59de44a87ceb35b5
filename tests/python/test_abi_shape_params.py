"""How cls(**params) maps to hr_param_spec: declared with a `params` dict or
from __init__'s signature, numbers and strings, ranges checked by the host,
SDL's positional order, and every refusal naming what is wrong."""

import math

import pytest

from abi_support import SceneContext, abi, destroy, ffi, lib, load_sdl


class Recorder:
    """keeps what it was made with"""

    made = []

    def __init__(self, **kwargs):
        Recorder.made.append(kwargs)

    def bounds(self):
        return ((-1, -1, -1), (1, 1, 1))

    def hit(self, origin, direction, tmin, tmax):
        return []


@pytest.fixture
def ctx():
    Recorder.made.clear()
    with SceneContext() as c:
        yield c


def spec_of(ctx, name):
    cls = ffi.new("hr_shape_class **")
    ctx.check(lib.hr_context_find_shape_class(ctx.ptr, name.encode(), cls, ffi.NULL))
    c = cls[0]
    specs = []
    for i in range(c.param_count):
        p = c.params[i]
        specs.append((ffi.string(p.name).decode(), p.type, p.required, p.default_number,
                      p.min, p.max, ffi.string(p.help).decode()))
    return c, specs


def test_params_dict_declares_order_defaults_ranges_and_help(ctx):
    class Declared(Recorder):
        params = {"height": 2.0, "sides": 6, "texture": "wood",
                  "power": abi.Param(2.5, min=0.1, max=10, help="exponent of the profile"),
                  "label": abi.Param(kind="string")}

    abi.register_shape("declared", Declared, context=ctx)
    c, specs = spec_of(ctx, "declared")
    N, S = lib.HR_PARAM_NUMBER, lib.HR_PARAM_STRING
    inf = math.inf
    assert specs == [("height", N, 0, 2.0, -inf, inf, ""), ("sides", N, 0, 6.0, -inf, inf, ""),
                     ("texture", S, 0, 0.0, -inf, inf, ""),
                     ("power", N, 0, 2.5, 0.1, 10.0, "exponent of the profile"),
                     ("label", S, 1, 0.0, -inf, inf, "")]
    assert ffi.string(c.help) == b"keeps what it was made with"
    assert c.flags == 0 and c.surface_count == 1

    # SDL: positional, in declared order; a whole number for an int default
    # comes back as int, an omitted string as the Python default.
    scene, _ = load_sdl(ctx, "declared 3 4 oak 7.5 tag\n")
    assert Recorder.made[-1] == {"height": 3.0, "sides": 4, "texture": "oak", "power": 7.5,
                                 "label": "tag"}
    assert type(Recorder.made[-1]["sides"]) is int
    destroy(scene)

    desc, keep = object_desc("declared", {"label": "x", "sides": 2.5})
    scene = new_scene(ctx)
    ctx.check(lib.hr_scene_add_object(scene, desc, ffi.NULL))
    assert Recorder.made[-1] == {"height": 2.0, "sides": 2.5, "texture": "wood", "power": 2.5,
                                 "label": "x"}


def object_desc(shape, params):
    keep = [ffi.new("char[]", shape.encode())]
    array = ffi.new("hr_param[]", max(len(params), 1))
    keep.append(array)
    for i, (name, value) in enumerate(params.items()):
        keep.append(ffi.new("char[]", name.encode()))
        array[i].name = keep[-1]
        if isinstance(value, str):
            keep.append(ffi.new("char[]", value.encode()))
            array[i].type, array[i].string = lib.HR_PARAM_STRING, keep[-1]
        else:
            array[i].type, array[i].number = lib.HR_PARAM_NUMBER, value
    desc = ffi.new("hr_object_desc *")
    desc.struct_size = ffi.sizeof("hr_object_desc")
    desc.shape = keep[0]
    desc.params = array
    desc.param_count = len(params)
    return desc, keep


def new_scene(ctx):
    out = ffi.new("hr_scene **")
    ctx.check(lib.hr_scene_create(ctx.ptr, out))
    ctx.scenes.append(out[0])
    from abi_support import _owners
    _owners[int(ffi.cast("uintptr_t", out[0]))] = ctx
    return out[0]


def test_init_signature_declares_the_params(ctx):
    class FromInit(Recorder):
        closed = True
        surface_count = 3
        help = "made from __init__"

        def __init__(self, radius=1.0, count=2, name: str = "n", *, scale, tag: str, **rest):
            Recorder.made.append(dict(radius=radius, count=count, name=name, scale=scale,
                                      tag=tag))

    abi.register_shape("from_init", FromInit, context=ctx)
    c, specs = spec_of(ctx, "from_init")
    assert [(s[0], s[1], s[2]) for s in specs] == [
        ("radius", lib.HR_PARAM_NUMBER, 0), ("count", lib.HR_PARAM_NUMBER, 0),
        ("name", lib.HR_PARAM_STRING, 0), ("scale", lib.HR_PARAM_NUMBER, 1),
        ("tag", lib.HR_PARAM_STRING, 1)]
    assert c.flags == lib.HR_SHAPE_CLOSED and c.surface_count == 3
    assert ffi.string(c.help) == b"made from __init__"
    scene, _ = load_sdl(ctx, "from_init 0.5 3 x 2 t\n")
    assert Recorder.made[-1] == dict(radius=0.5, count=3, name="x", scale=2.0, tag="t")
    destroy(scene)


def test_surface_names_name_each_surface_id(ctx):
    class Named(Recorder):
        params = {}
        surface_names = ("wall", "cap")

    abi.register_shape("named", Named, context=ctx)
    c, _ = spec_of(ctx, "named")
    assert c.surface_count == 2  # from the names
    assert [ffi.string(c.surface_names[i]) for i in range(2)] == [b"wall", b"cap"]
    abi.register_shape("unnamed", type("Unnamed", (Recorder,), {"params": {}}), context=ctx)
    assert spec_of(ctx, "unnamed")[0].surface_names == ffi.NULL
    for names, count in ((["a", "b"], 3), (["a", ""], 2), ("ab", 2), (["a", 1], 2)):
        bad = type("B", (Recorder,), {"params": {}, "surface_names": names, "surface_count": count})
        with pytest.raises(ValueError, match="surface_names"):
            abi.register_shape("bad", bad, context=ctx)


def test_a_class_without_params(ctx):
    class Bare:
        def bounds(self):
            return None

        def hit(self, origin, direction, tmin, tmax):
            return []

    abi.register_shape("bare", Bare, context=ctx)
    c, specs = spec_of(ctx, "bare")
    assert specs == [] and c.params == ffi.NULL
    assert ffi.string(c.help).startswith(b"a shape written in Python")
    scene, _ = load_sdl(ctx, "bare\n")
    destroy(scene)


def sdl_error(ctx, text):
    with pytest.raises(abi.HitrayError) as e:
        load_sdl(ctx, text)
    return e.value


def test_the_host_checks_ranges_and_required_params(ctx):
    class Ranged(Recorder):
        params = {"power": abi.Param(2.0, min=1, max=4), "need": abi.Param()}

    abi.register_shape("ranged", Ranged, context=ctx)
    e = sdl_error(ctx, "ranged 5 1\n")
    assert e.status == lib.HR_ERROR_PARAMETER
    assert "test.sdl:1:1" in str(e) and "parameter 'power' = 5 is outside [1, 4]" in str(e)
    scene = new_scene(ctx)
    desc, keep = object_desc("ranged", {"power": 2})
    with pytest.raises(abi.HitrayError) as e:
        ctx.check(lib.hr_scene_add_object(scene, desc, ffi.NULL))
    assert "parameter 'need' is required" in str(e.value)
    e = sdl_error(ctx, "ranged 2\n")
    assert "expected a number after 'ranged'" in str(e)
    assert Recorder.made == []


def test_create_failures_carry_the_python_message(ctx):
    class Picky(Recorder):
        def __init__(self, radius=1.0):
            if radius < 0:
                raise ValueError(f"radius must be >= 0, not {radius}")

    abi.register_shape("picky", Picky, context=ctx)
    e = sdl_error(ctx, "light 1 1 1 1 1 1\npicky -2\n")
    assert e.status == lib.HR_ERROR_PARAMETER
    message = str(e)
    assert message.startswith("test.sdl:2:1")
    assert "ValueError: radius must be >= 0, not -2.0" in message
    assert "python:" in message and "Picky" in message  # the origin names the class
    assert message.count("radius must be") == 1
    assert isinstance(e.__cause__, abi.ShapeError)
    assert isinstance(e.__cause__.__cause__, ValueError)


@pytest.mark.parametrize("bounds, complaint", [
    ((1, 2), "bounds() must return"),
    (((0, 0, 0), (1, 1)), "bounds() must return"),
    (((0, 0, 0), (1, -1, 1)), "each min must be <= its max"),
    (((0, math.nan, 0), (1, 1, 1)), "none may be NaN"),
    ("box", "bounds() must return"),
])
def test_bad_bounds_refuse_the_object(ctx, bounds, complaint):
    class BadBounds(Recorder):
        params = {}

        def bounds(self):
            return bounds

    abi.register_shape("badbounds", BadBounds, context=ctx)
    e = sdl_error(ctx, "badbounds\n")
    assert e.status == lib.HR_ERROR_PARAMETER and complaint in str(e)


def test_a_bounds_method_that_raises_refuses_the_object(ctx):
    class Raises(Recorder):
        params = {}

        def bounds(self):
            raise RuntimeError("no idea")

    abi.register_shape("raises", Raises, context=ctx)
    e = sdl_error(ctx, "raises\n")
    assert "bounds() raised RuntimeError: no idea" in str(e)


@pytest.mark.parametrize("params, complaint", [
    ({"r": [1]}, "default [1] is neither a number nor a string"),
    ({"r": math.inf}, "default inf is not a finite number"),
    ({"r": True}, "neither a number nor a string"),
    ({"r": abi.Param(5, min=0, max=1)}, "default 5 is outside [0, 1]"),
    ({"r": abi.Param(0.5, min=1, max=0)}, "is not a range of numbers"),
    ({"r": abi.Param("a", min=0, max=1)}, "a string parameter has no range"),
    ({"r": abi.Param(1, kind="vector")}, "kind must be 'number' or 'string'"),
    ({"not valid": 1}, "is not a Python identifier"),
    ([("r", 1)], "'params' must be a dict"),
])
def test_bad_param_declarations_are_refused_at_registration(ctx, params, complaint):
    class Bad(Recorder):
        pass

    Bad.params = params
    with pytest.raises(ValueError) as e:
        abi.register_shape("bad", Bad, context=ctx)
    assert complaint in str(e.value) and "Bad" in str(e.value)


def test_register_shape_refuses_what_cannot_be_a_shape(ctx):
    with pytest.raises(ValueError, match="must be a word"):
        abi.register_shape("two words", Recorder, context=ctx)
    with pytest.raises(ValueError, match="must be a word"):
        abi.register_shape("9lives", Recorder, context=ctx)
    with pytest.raises(TypeError, match="takes a class"):
        abi.register_shape("inst", Recorder(), context=ctx)

    class NoHit:
        def bounds(self):
            return None

    with pytest.raises(TypeError, match="no method hit"):
        abi.register_shape("nohit", NoHit, context=ctx)

    class Positional(Recorder):
        def __init__(self, r, /):
            pass

    with pytest.raises(ValueError, match="positional-only"):
        abi.register_shape("positional", Positional, context=ctx)
    with pytest.raises(TypeError, match="context must be"):
        abi.register_shape("ok", Recorder, context=42)
    with pytest.raises(ValueError, match="surface_count"):
        abi.register_shape("ok", type("S", (Recorder,), {"params": {}, "surface_count": 0}), context=ctx)
    with pytest.raises(ValueError, match="hit_relative_error"):
        abi.register_shape("ok", type("E", (Recorder,), {"params": {}, "hit_relative_error": -1}),
                           context=ctx)


def test_an_init_of_only_var_keywords_is_refused_at_registration_with_the_fix(ctx):
    """__init__(self, **params) declares no parameter the host can check: it
    was accepted and then every scene line with a parameter refused as
    "takes no parameters". Refused at register_shape, saying how to declare
    them; with named parameters beside **rest, those are the parameters."""
    class OnlyKeywords:
        def __init__(self, **params):
            self.params_given = params

        def bounds(self):
            return None

        def hit(self, origin, direction, tmin, tmax):
            return []

    with pytest.raises(ValueError) as e:
        abi.register_shape("onlykw", OnlyKeywords, context=ctx)
    assert "OnlyKeywords" in str(e.value) and "**params" in str(e.value)
    assert "params = {" in str(e.value)

    class NamedAndRest(OnlyKeywords):
        def __init__(self, radius=1.0, **rest):
            super().__init__(radius=radius, **rest)

    abi.register_shape("namedrest", NamedAndRest, context=ctx)
    _, specs = spec_of(ctx, "namedrest")
    assert [s[0] for s in specs] == ["radius"]
    scene, _ = load_sdl(ctx, "namedrest 2\n")
    destroy(scene)
