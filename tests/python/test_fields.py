"""The material and global fields come from one table of the library
(include/hitray/scene_fields.h): the extension lists them, and SDL's reader,
the extension's conversions and the package agree on every one."""

import pytest

import hitray
from hitray import _core, material

# A value of each kind that every field of that kind takes, in SDL and in
# Python (the one integer of a material is its texture: -1 the checkerboard).
SDL_VALUE = {"color": "0.25 0.5 0.75", "number": "0.5", "integer": "2"}
PYTHON_VALUE = {"color": (0.25, 0.5, 0.75), "number": 0.5, "integer": 2}


def test_the_extension_lists_every_field_once_with_a_known_kind():
    for fields, kinds in ((_core.material_fields(), {"color", "number", "integer", "numbers"}),
                          (_core.global_fields(), {"color", "number", "integer"})):
        names = [name for name, _, _ in fields]
        words = [word for _, word, _ in fields]
        assert len(set(names)) == len(names) and len(set(words)) == len(words)
        assert {kind for _, _, kind in fields} == kinds


def test_every_material_field_is_read_by_its_sdl_word_and_its_python_name():
    fields = _core.material_fields()
    assert set(material.MATERIAL_NAMES) == ({n for n, _, _ in fields} | {w for _, w, _ in fields})
    for name, word, kind in fields:
        if kind == "numbers":
            sdl, value = f"{word} 2 1 2.5", (1.0, 2.5)
        elif kind == "integer":
            sdl, value = f"{word} -1", -1
        else:
            sdl, value = f"{word} {SDL_VALUE[kind]}", PYTHON_VALUE[kind]
        scene, _ = hitray.parse_sdl(f"{sdl} sphere")
        from_sdl = scene.objects[0].material
        assert from_sdl[name] == value, word
        # The object's material lists every field, in the table's order.
        assert list(from_sdl) == [n for n, _, _ in fields]
        for key in {name, word}:
            built = hitray.Scene()
            assert built.add(hitray.Sphere(), **{key: value}).material == from_sdl, key


def test_every_global_is_a_documented_property_with_its_sdl_word_as_alias():
    for name, word, kind in _core.global_fields():
        prop = vars(hitray.Scene)[name]
        assert isinstance(prop, property) and prop.__doc__, name
        scene, _ = hitray.parse_sdl(f"{word} {SDL_VALUE[kind]} sphere")
        value = PYTHON_VALUE[kind]
        assert getattr(scene, name) == value and getattr(scene, word) == value, word
        built = hitray.Scene()
        setattr(built, word, value)
        assert getattr(built, name) == value


def test_an_unknown_field_is_refused_by_the_extension():
    with pytest.raises(TypeError, match="unknown field 'shininess'"):
        _core.Scene().add_object("sphere", [], {"shininess": 1.0}, hitray.Sphere()._transform, b"")
    with pytest.raises(TypeError, match="unknown global 'fog'"):
        _core.Scene().set_globals({"fog": 1.0})
