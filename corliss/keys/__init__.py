"""The scene's keys, the lowest room: what a key is and how it is read and written.

Every other room may import this one, the physics packages (valves, governors) too;
it imports nothing of the package but :mod:`corliss.errors`.

- :mod:`corliss.keys.units`: quantity strings to SI and back;
- :mod:`corliss.keys.declared`: the declared keys of a section, gear, governor or effect;
- :mod:`corliss.keys.toml_table`: one TOML table read by typed getters that name the key;
- :mod:`corliss.keys.registry`: the registries of valve gears and governors by name;
- :mod:`corliss.keys.edits`: ``KEY=LOW:HIGH`` ranges and scenes edited by key;
- :mod:`corliss.keys.textfiles`: the text files a user gives, read with clear errors;
- :mod:`corliss.keys.toml_text`: a scene's tables written back as TOML text.
"""
