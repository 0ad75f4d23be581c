"""FC43/14 device identification objects read against the slave's profile ([objects.N]): the text a
known object means, its revision form, and a value longer than the device allows (annotator.py calls it)."""
from __future__ import annotations

from dissector.devices.profiles import Profile
from dissector.model import DeviceObject, Frame
from dissector.protocol.rules import text


def check_objects(frame: Frame, profile: Profile, objects: list[DeviceObject]) -> None:
    sent = frame.fields["body"]["objects"]  # (the bytes sent: a value shows other bytes than ASCII as \xNN)
    for obj, fields in zip(objects, sent):
        meaning = profile.objects.get(obj.id)
        if meaning is None:
            continue
        size = len(fields.value)
        if meaning.max_length is not None and size > meaning.max_length:
            frame.warnings.append(text("object_length", object=obj.name, length=size, device=profile.device,
                                       limit=meaning.max_length))
        if meaning.format == "MMmm":
            value = obj.value
            if len(value) == 4 and value.isascii() and value.isdigit():
                obj.text = f"V{int(value[:2])}.{int(value[2:])}"
                continue
            frame.notes.append(text("revision_form", object=obj.name, value=value, device=profile.device))
        obj.text = meaning.meaning
