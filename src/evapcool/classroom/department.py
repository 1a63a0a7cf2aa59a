"""A department's server: its room is views/department.py (the administrator's and
lecturers' calls and pages, joining by code); its names stay importable from here."""

from __future__ import annotations

from evapcool.classroom.views.admin import admin_page, admin_post
from evapcool.classroom.views.department import (
    FORM_BYTES,
    POLICY,
    ROOT_ROUTES,
    ROUTES,
    STYLE,
    TITLE_MAX,
    admin_classes,
    admin_lecturers,
    class_doc,
    classes_page,
    classes_post,
    clean_title,
    listed_rooms,
    my_classes,
    new_admin_token,
    new_token,
)
from evapcool.classroom.views.join import join_page

__all__ = [
    "FORM_BYTES",
    "POLICY",
    "ROOT_ROUTES",
    "ROUTES",
    "STYLE",
    "TITLE_MAX",
    "admin_classes",
    "admin_lecturers",
    "admin_page",
    "admin_post",
    "class_doc",
    "classes_page",
    "classes_post",
    "clean_title",
    "join_page",
    "listed_rooms",
    "my_classes",
    "new_admin_token",
    "new_token",
]
