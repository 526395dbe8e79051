"""``ladev serve-policy NAME --port P``: serve a policy over openpi's websocket protocol."""

from __future__ import annotations

import ipaddress
import logging
import os

import click


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


@click.command()
@click.argument("name")
@click.option("--port", default=8000, show_default=True, type=int, help="TCP port (0: any free port).")
@click.option(
    "--host",
    default="127.0.0.1",
    show_default=True,
    help="Interface to bind. Loopback by default; 0.0.0.0 exposes the policy to the network.",
)
@click.option(
    "--api-key-env",
    default=None,
    metavar="VAR",
    help="Require clients to send the API key held in this environment variable.",
)
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="KEY=VALUE",
    help="Override a policy config value (YAML), e.g. --set robot=widowx. Repeatable.",
)
@click.option("--max-connections", default=1, show_default=True, type=int,
              help="Clients served at once (more than 1 only for stateless policies).")
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
@click.option("--log-level", default="info", show_default=True,
              type=click.Choice(["debug", "info", "warning", "error"]))
def command(
    name: str,
    port: int,
    host: str,
    api_key_env: str | None,
    overrides: tuple[str, ...],
    max_connections: int,
    config_dir: str | None,
    log_level: str,
) -> None:
    """Serve the policy NAME (a conf/policy entry such as rt1_x, or a registered name).

    Clients: the `remote` policy (policy=remote in a study) or any openpi client.
    GET /healthz answers 200 when the server is up.
    """
    from ladev_lib.policies.configured import make_configured_policy, parse_overrides
    from ladev_lib.serving.server import PolicyServer

    logging.basicConfig(level=log_level.upper(), format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    api_key = None
    if api_key_env:
        api_key = os.environ.get(api_key_env)
        if not api_key:
            raise click.UsageError(f"--api-key-env {api_key_env}: that environment variable is not set")
    if not _is_loopback(host) and api_key is None:
        click.secho(
            f"warning: serving on {host} without an API key; anyone who can reach this port "
            "can drive the policy (use --api-key-env)",
            fg="yellow",
            err=True,
        )
    policy = make_configured_policy(name, config_dir, parse_overrides(overrides))
    server = PolicyServer(
        policy, host=host, port=port, api_key=api_key, max_connections=max_connections
    )

    def ready(srv: object) -> None:
        for sock in getattr(srv, "sockets", ()):
            bound_host, bound_port = sock.getsockname()[:2]
            click.echo(f"serving {policy.info.name!r} on ws://{bound_host}:{bound_port} "
                       f"(health: http://{bound_host}:{bound_port}/healthz)", err=True)

    server.run(on_ready=ready)
