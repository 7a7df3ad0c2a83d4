"""``dataclass`` as the standard library's, but cheap to define: mech's start-up is benchmarked.

``dataclasses.dataclass`` compiles its ``__init__``, ``__repr__``, ``__eq__``,
``__hash__``, ``__setattr__`` and ``__delattr__`` from source text when the
class is *defined*: about a millisecond per frozen, slotted class, ~40 ms of a
``mech dof`` that defines some forty classes and uses a dozen.  This
``dataclass`` lets the standard library read the fields (so ``fields``,
``replace``, ``asdict`` and ``__match_args__`` work as always) but generates
nothing; the methods are small closures over the field list, except
``__init__``, which is compiled as the standard library would compile it the
first time the class is instantiated.  Type checkers see
``dataclasses.dataclass`` itself.

Supported: ``frozen``, ``slots``, ``eq``, ``repr`` and fields with defaults,
default factories, ``compare``/``repr``/``hash`` flags and ``__post_init__``;
any other option is handed to the standard library unchanged.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

__all__ = ["dataclass"]

if TYPE_CHECKING:
    from dataclasses import dataclass as dataclass
else:
    import dataclasses as _dc

    _MISSING = _dc.MISSING
    _setattr = object.__setattr__

    def dataclass(cls=None, /, *, frozen=False, slots=False, eq=True, repr=True, **options):
        """Drop-in for :func:`dataclasses.dataclass` (see the module's docstring)."""

        def wrap(c):
            if options or any(k in c.__dict__ for k in ("__slots__", "__setattr__", "__delattr__")):
                return _dc.dataclass(c, frozen=frozen, slots=slots, eq=eq, repr=repr, **options)
            try:
                return _build(c, frozen, slots, eq, repr)
            except TypeError:  # e.g. a frozen base under a plain class: let the library say so
                return _dc.dataclass(c, frozen=frozen, slots=slots, eq=eq, repr=repr)

        return wrap if cls is None else wrap(cls)

    def _build(cls, frozen, slots, eq, want_repr):
        own = set(cls.__dict__)
        if cls.__dict__.get("__hash__", 0) is None and "__eq__" in own:
            own.discard("__hash__")  # set to None by Python for defining __eq__: not an explicit hash
        if not cls.__dict__.get("__doc__"):  # the library would build one with inspect.signature
            cls.__doc__ = f"{cls.__name__}(...)"
        cls = _dc.dataclass(cls, init=False, repr=False, eq=False)  # fields only: nothing compiled
        fields = _dc.fields(cls)
        names = tuple(f.name for f in fields)
        if slots:
            cls = _slotted(cls, names)
        if "__init__" not in own:
            cls.__init__ = _first_init(fields)
        if want_repr and "__repr__" not in own:
            shown = tuple(f.name for f in fields if f.repr)

            def __repr__(self):
                inner = ", ".join(f"{n}={getattr(self, n)!r}" for n in shown)
                return f"{type(self).__qualname__}({inner})"

            cls.__repr__ = __repr__
        if eq and "__eq__" not in own:
            compared = tuple(f.name for f in fields if f.compare)

            def __eq__(self, other):
                if other.__class__ is not self.__class__:
                    return NotImplemented
                # tuples, as the standard library compares (identity first: a NaN equals itself)
                return tuple(getattr(self, n) for n in compared) == tuple(getattr(other, n) for n in compared)

            cls.__eq__ = __eq__
            if "__hash__" not in own:
                if frozen:
                    hashed = tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))

                    def __hash__(self):
                        return hash(tuple(getattr(self, n) for n in hashed))

                    cls.__hash__ = __hash__
                else:
                    cls.__hash__ = None
        if frozen:
            fieldset = frozenset(names)

            def __setattr__(self, name, value):
                if type(self) is cls or name in fieldset:
                    raise _dc.FrozenInstanceError(f"cannot assign to field {name!r}")
                super(cls, self).__setattr__(name, value)

            def __delattr__(self, name):
                if type(self) is cls or name in fieldset:
                    raise _dc.FrozenInstanceError(f"cannot delete field {name!r}")
                super(cls, self).__delattr__(name)

            cls.__setattr__, cls.__delattr__ = __setattr__, __delattr__
            if slots:

                def __getstate__(self):
                    return [getattr(self, n) for n in names]

                def __setstate__(self, state):
                    for n, v in zip(names, state, strict=True):
                        _setattr(self, n, v)

                cls.__getstate__, cls.__setstate__ = __getstate__, __setstate__
        for name in ("__init__", "__repr__", "__eq__", "__hash__", "__setattr__", "__delattr__"):
            fn = cls.__dict__.get(name)
            if fn is not None and getattr(fn, "__qualname__", "").startswith("_build."):
                fn.__qualname__ = f"{cls.__qualname__}.{name}"
        return cls

    def _slotted(cls, names):
        """The class again with ``__slots__`` for its own fields (as ``dataclass(slots=True)`` does)."""
        body = dict(cls.__dict__)
        inherited = {s for base in cls.__mro__[1:-1] for s in getattr(base, "__slots__", ())}
        body["__slots__"] = tuple(n for n in names if n not in inherited)
        for n in names:
            body.pop(n, None)  # class-level defaults would shadow the slots
        body.pop("__dict__", None)
        body.pop("__weakref__", None)
        qualname = getattr(cls, "__qualname__", None)
        new = type(cls)(cls.__name__, cls.__bases__, body)
        if qualname is not None:
            new.__qualname__ = qualname
        return new

    def _first_init(fields):
        """A generic ``__init__`` that, from the class's 16th instance on, compiles the real one.

        Classes instantiated a few times (module constants, one file's model)
        never pay for compiling; busy ones get the standard library's code.
        """
        plain = tuple(f.name for f in fields if f.init)
        computed = tuple(
            f
            for f in fields
            if not f.init and (f.default is not _MISSING or f.default_factory is not _MISSING)
        )
        defaults = {}
        for f in fields:
            if f.init and f.default is not _MISSING:
                defaults[f.name] = lambda d=f.default: d
            elif f.init and f.default_factory is not _MISSING:
                defaults[f.name] = f.default_factory
        calls = [0]

        def __init__(self, *args, **kwargs):
            calls[0] += 1
            if calls[0] > 15:
                cls = type(self)
                owner = next(c for c in cls.__mro__ if c.__dict__.get("__init__") is __init__)
                owner.__init__ = _compile_init(owner, fields)
                owner.__init__(self, *args, **kwargs)
                return
            if len(args) > len(plain):
                raise TypeError(
                    f"__init__() takes {len(plain) + 1} positional arguments but {len(args) + 1} were given"
                )
            values = dict(zip(plain, args, strict=False))  # fewer args than fields: defaults
            for k, v in kwargs.items():
                if k not in defaults and k not in plain:
                    raise TypeError(f"__init__() got an unexpected keyword argument {k!r}")
                if k in values:
                    raise TypeError(f"__init__() got multiple values for argument {k!r}")
                values[k] = v
            for n in plain:
                if n in values:
                    _setattr(self, n, values[n])
                elif n in defaults:
                    _setattr(self, n, defaults[n]())
                else:
                    raise TypeError(f"__init__() missing 1 required positional argument: {n!r}")
            for f in computed:
                _setattr(self, f.name, f.default if f.default is not _MISSING else f.default_factory())
            post = getattr(self, "__post_init__", None)
            if post is not None:
                post()

        return __init__

    def _compile_init(cls, fields):
        params, body = [], []
        env = {"__set": _setattr, "__MISSING": _MISSING}
        for f in fields:
            value = f.name
            if f.default is not _MISSING:
                env[f"__d_{f.name}"] = f.default
                default = f"=__d_{f.name}"
            elif f.default_factory is not _MISSING:
                env[f"__f_{f.name}"] = f.default_factory
                default = "=__MISSING"
                value = f"(__f_{f.name}() if {f.name} is __MISSING else {f.name})"
            else:
                default = ""
            if f.init:
                params.append(f"{f.name}{default}")
            elif f.default is not _MISSING:
                value = f"__d_{f.name}"
            elif f.default_factory is not _MISSING:
                value = f"__f_{f.name}()"
            else:
                continue
            body.append(f"  __set(self, {f.name!r}, {value})")
        if hasattr(cls, "__post_init__"):
            body.append("  self.__post_init__()")
        src = f"def __init__(self, {', '.join(params)}):\n" + ("\n".join(body) or "  pass") + "\n"
        ns = {}
        exec(src, env, ns)
        fn = ns["__init__"]
        fn.__qualname__ = f"{cls.__qualname__}.__init__"
        return fn
