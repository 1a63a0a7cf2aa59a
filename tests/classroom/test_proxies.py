"""The department's reverse proxies as the class guide gives them, really started: Debian's
nginx and Caddy over HTTPS in front of two server processes on one PostgreSQL, each process
started with the options of the guide's systemd unit. The configurations are read from
docs/class.md; only ports, certificate files and the folders the proxies write in are put in
(Caddy's certificate from its own local authority instead of the public one)."""

from __future__ import annotations

import asyncio
import json
import os
import re
import shlex
import shutil
import ssl
import subprocess
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, code, free_port, start_server
from pghelp import Postgres

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "class.md"
HOST = "class.example.edu"
#: A generous bound for a proxy to start and for a board to arrive (no speed asserted).
WAIT = 30.0
#: Two students' own addresses (loopback aliases: the proxy sees them as clients).
STUDENT_A, STUDENT_B = "127.0.0.2", "127.0.0.3"


def guide_block(marker: str) -> str:
    """The first ```text block after `marker` in the class guide."""
    text = GUIDE.read_text(encoding="utf-8")
    start = text.index("```text\n", text.index(marker)) + len("```text\n")
    return text[start : text.index("```", start)]


def put(text: str, old: str, new: str) -> str:
    """text with old replaced by new (old must be there: the guide changed otherwise)."""
    assert old in text, f"the guide's block no longer has {old!r}"
    return text.replace(old, new)


def unit_options(public: str) -> tuple[str, ...]:
    """The server's options from the guide's systemd unit, less those the test sets (--port,
    --db, --workers), with its public address put in."""
    unit = guide_block("evapcool-class@.service")
    line = re.search(r"^ExecStart=(.*?)(?<!\\)$", unit.replace("\\\n", " "), re.M)
    assert line, "no ExecStart in the guide's unit"
    words = shlex.split(line.group(1))[2:]  # after the program and `class`
    options: list[str] = []
    while words:
        word = words.pop(0)
        if word in ("--port", "--db", "--workers"):
            words.pop(0)
        elif word == "--public-url":
            assert words.pop(0).startswith(f"https://{HOST}")
            options += [word, public]
        else:
            options.append(word)
    return tuple(options)


@dataclass
class Proxied:
    """A proxy on 127.0.0.1:port before two servers; `authority`: its CA certificate."""

    name: str
    port: int
    servers: list[Server]
    authority: Path

    @property
    def public(self) -> str:
        return f"https://{HOST}:{self.port}"

    def client(self, source: str | None = None, **kw: Any) -> httpx.AsyncClient:
        """A client of the proxy as a browser at `public` would be (TLS checked against the
        authority for HOST), connecting from `source` if given."""

        async def named(request: httpx.Request) -> None:
            request.extensions["sni_hostname"] = HOST
            request.headers["Host"] = f"{HOST}:{self.port}"

        trust = ssl.create_default_context(cafile=str(self.authority))
        transport = httpx.AsyncHTTPTransport(
            verify=trust, **({"local_address": source} if source else {})
        )
        return httpx.AsyncClient(
            base_url=f"https://127.0.0.1:{self.port}",
            transport=transport,
            event_hooks={"request": [named]},
            timeout=WAIT,
            **kw,
        )


def _certificate(folder: Path) -> tuple[Path, Path]:
    """A self-signed certificate for HOST (the file is its own authority)."""
    cert, key = folder / "class.pem", folder / "class.key"
    subprocess.run(
        ["openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:P-256",
         "-nodes", "-days", "2", "-subj", f"/CN={HOST}", "-addext", f"subjectAltName=DNS:{HOST}",
         "-keyout", str(key), "-out", str(cert)],
        check=True, capture_output=True,
    )  # fmt: skip
    return cert, key


def _nginx(folder: Path, port: int, upstreams: tuple[int, int]) -> tuple[list[str], Path]:
    """nginx's command and authority: the guide's upstream and server blocks in an http
    block of the test's own."""
    cert, key = _certificate(folder)
    site = guide_block("or nginx (")
    site = put(site, "listen 443 ssl;", f"listen 127.0.0.1:{port} ssl;")
    site = put(site, "server 127.0.0.1:8765;", f"server 127.0.0.1:{upstreams[0]};")
    site = put(site, "server 127.0.0.1:8766;", f"server 127.0.0.1:{upstreams[1]};")
    site = put(site, "/etc/ssl/class.example.edu.pem", str(cert))
    site = put(site, "/etc/ssl/class.example.edu.key", str(key))
    temp = "\n".join(
        f"  {kind}_temp_path {folder}/{kind};"
        for kind in ("client_body", "proxy", "fastcgi", "uwsgi", "scgi")
    )
    conf = folder / "nginx.conf"
    conf.write_text(
        ("user root;\n" if os.geteuid() == 0 else "")
        + f"daemon off;\npid {folder}/nginx.pid;\nerror_log {folder}/error.log;\n"
        + "events { worker_connections 512; }\n"
        + f"http {{\n  access_log off;\n{temp}\n{site}\n}}\n",
        encoding="utf-8",
    )
    nginx = shutil.which("nginx") or "/usr/sbin/nginx"
    return [nginx, "-e", f"{folder}/error.log", "-p", str(folder), "-c", str(conf)], cert


def _caddy(folder: Path, port: int, upstreams: tuple[int, int]) -> tuple[list[str], Path]:
    """Caddy's command and authority: the guide's site block, the site on the test's port
    (on 127.0.0.1 only), certificates from Caddy's local authority kept in `folder`."""
    site = guide_block("Caddy (`/etc/caddy/Caddyfile`)")
    site = put(site, f"{HOST} {{", f"{HOST}:{port} {{")
    site = put(
        site, "127.0.0.1:8765 127.0.0.1:8766", f"127.0.0.1:{upstreams[0]} 127.0.0.1:{upstreams[1]}"
    )
    options = (
        f"{{\n  admin off\n  default_bind 127.0.0.1\n  local_certs\n  skip_install_trust\n"
        f"  http_port {free_port()}\n"
        "  grace_period 2s\n"
        f"  storage file_system {folder}/data\n}}\n"
    )
    conf = folder / "Caddyfile"
    conf.write_text(options + site, encoding="utf-8")
    authority = folder / "data" / "pki" / "authorities" / "local" / "root.crt"
    caddy = shutil.which("caddy") or "/usr/bin/caddy"
    return [caddy, "run", "--config", str(conf), "--adapter", "caddyfile"], authority


def _answers(proxied: Proxied) -> bool:
    async def ask() -> bool:
        async with proxied.client() as client:
            return (await client.get("/api/leaderboard")).status_code == 200

    try:
        return proxied.authority.exists() and asyncio.run(ask())
    except (httpx.TransportError, OSError):
        return False


@pytest.fixture(scope="module", params=["nginx", "caddy"])
def proxied(
    request: pytest.FixtureRequest, postgres: Postgres, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Proxied]:
    """The proxy named by the parameter before two department servers; stopped after."""
    name = str(request.param)
    if (
        not shutil.which(name)
        and not Path(f"/usr/{'s' if name == 'nginx' else ''}bin/{name}").exists()
    ):
        pytest.skip(f"{name} is not installed (Debian: apt-get install {name})")
    folder = tmp_path_factory.mktemp(name)
    folder.chmod(0o755)  # nginx's workers write their temporary files there
    url, port, upstreams = postgres.new_database(), free_port(), (free_port(), free_port())
    options = unit_options(f"https://{HOST}:{port}")
    first = start_server(url, port=upstreams[0], extra=options)
    servers = [first]
    try:
        servers.append(start_server(url, port=upstreams[1], token=first.token, extra=options))
        command, authority = (_nginx if name == "nginx" else _caddy)(folder, port, upstreams)
        env = {**os.environ, "HOME": str(folder), "XDG_DATA_HOME": str(folder / "data"),
               "XDG_CONFIG_HOME": str(folder / "config")}  # fmt: skip
        log = (folder / "proxy.log").open("wb")
        proc = subprocess.Popen(command, env=env, stdout=log, stderr=log)
        try:
            proxied = Proxied(name, port, servers, authority)
            deadline = time.monotonic() + WAIT
            while not _answers(proxied):
                assert proc.poll() is None, f"{name} ended: {(folder / 'proxy.log').read_text()}"
                assert time.monotonic() < deadline, f"{name} did not answer in {WAIT} s"
                time.sleep(0.2)
            yield proxied
        finally:
            proc.terminate()
            try:
                proc.wait(15)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(15)
            log.close()
    finally:
        for server in servers:
            server.stop()


async def _a_class(
    proxied: Proxied, client: httpx.AsyncClient
) -> tuple[dict[str, Any], dict[str, str], int]:
    """(the class's document, its lecturer's header, its open challenge), all made through the
    proxy."""
    admin = {"Authorization": f"Bearer {proxied.servers[0].token}"}
    made = await client.post("/api/admin/lecturers", json={"name": "Ada"}, headers=admin)
    assert made.status_code == 200, made.text
    lecturer = {"Authorization": f"Bearer {made.json()['token']}"}
    room = await client.post("/api/classes", json={"name": "Hall"}, headers=lecturer)
    assert room.status_code == 200, room.text
    body = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}
    base = f"/c/{room.json()['code']}/"
    opened = await client.post(
        base + "api/challenge", json={**body, "seed": SEED}, headers=lecturer
    )
    assert opened.status_code == 200, opened.text
    return room.json(), lecturer, int(opened.json()["id"])


def test_the_projector_and_the_links_show_the_public_address(proxied: Proxied) -> None:
    async def run() -> tuple[dict[str, Any], str]:
        async with proxied.client() as client:
            room, _, _ = await _a_class(proxied, client)
            page = await client.get(room["projector"])
            assert page.status_code == 200, page.text
            return room, page.text

    room, page = asyncio.run(run())
    join = f"{proxied.public}/c/{room['code']}/"
    assert room["join"] == join
    # The projector says the public address short (no scheme) over the class's join code
    # (issue 45), and no "phones cannot reach" warning.
    short = proxied.public.split("://", 1)[1].rstrip("/")
    assert f'<span class="address">{short}</span><' in page and f">{room['code']}<" in page
    assert 'id="loopback"' not in page


async def _boards(client: httpx.AsyncClient, path: str, names: set[str]) -> list[str]:
    """Follow a board's stream until every name is on it; the names seen then."""
    async with client.stream("GET", path) as events:
        assert events.status_code == 200
        async for line in events.aiter_lines():
            if line.startswith("data: "):
                seen = {e["name"] for e in json.loads(line[6:])["entries"]}
                if names <= seen:
                    return sorted(seen)
    raise AssertionError("the stream ended")


def test_a_game_sent_through_the_proxy_reaches_a_stream_through_it(proxied: Proxied) -> None:
    async def run() -> list[str]:
        async with proxied.client() as client:
            room, _, challenge = await _a_class(proxied, client)
            base = f"/c/{room['code']}/"
            joined = await client.post(base + "api/join", json={"name": "Via"})
            assert joined.status_code == 200, joined.text
            who = {"Authorization": f"Bearer {joined.json()['token']}"}
            watching = asyncio.create_task(_boards(client, base + "api/stream", {"Via"}))
            await asyncio.sleep(0.5)  # the stream is open
            game = {"challenge": challenge, "code": code(SEED, 1)}
            sent = await client.post(base + "api/submit", json=game, headers=who)
            assert sent.status_code == 200, sent.text
            return await asyncio.wait_for(watching, WAIT)

    assert asyncio.run(run()) == ["Via"]


def test_the_limits_count_each_students_address_not_the_proxys(proxied: Proxied) -> None:
    """A's streams reach the bound of both processes (20 each); B, at another address,
    still gets one. Were the proxy's own address counted, B would be refused too."""

    async def run() -> tuple[list[int], int]:
        async with proxied.client() as setup:
            room, _, _ = await _a_class(proxied, setup)
        path = f"/c/{room['code']}/api/stream"
        async with proxied.client(STUDENT_A) as a, proxied.client(STUDENT_B) as b:
            opened, statuses = [], []
            try:
                for _ in range(2 * 20 + 2):
                    response = await a.send(a.build_request("GET", path), stream=True)
                    statuses.append(response.status_code)
                    opened.append(response)
                other = await b.get(path.replace("api/stream", "api/leaderboard"))
                assert other.status_code == 200
                response = await b.send(b.build_request("GET", path), stream=True)
                opened.append(response)
                return statuses, response.status_code
            finally:
                for response in opened:
                    await response.aclose()

    statuses, b_status = asyncio.run(run())
    assert statuses.count(200) == 40 and statuses[-1] == 429, statuses
    assert b_status == 200


def test_one_process_killed_the_proxy_carries_on(proxied: Proxied) -> None:
    """kill -9 of one process: every request after it is answered by the other (the last
    test of each proxy: the process stays down)."""
    proxied.servers[1].stop(kill=True)

    async def run() -> list[int]:
        async with proxied.client() as client:
            room, _, _ = await _a_class(proxied, client)
            base = f"/c/{room['code']}/"
            answers = []
            for k in range(8):
                answers.append((await client.get(base + "api/leaderboard")).status_code)
                answers.append(
                    (await client.post(base + "api/join", json={"name": f"S{k}"})).status_code
                )
            return answers

    answers = asyncio.run(run())
    assert answers == [200] * len(answers), answers


def test_an_address_without_its_last_slash_stays_on_https(proxied: Proxied) -> None:
    async def run() -> httpx.Response:
        async with proxied.client() as client:
            room, _, _ = await _a_class(proxied, client)
            return await client.get(f"/c/{room['code']}")

    answer = asyncio.run(run())
    assert answer.status_code in (200, 301, 302, 307, 308), answer.status_code
    if answer.is_redirect:
        assert answer.headers["location"].startswith((f"{proxied.public}/", "/")), answer.headers
