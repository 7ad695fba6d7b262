"""The studio server's identity: jupyter_server's token, refused requests, and the page's XSRF cookie.

Voila (``make studio``) loads :class:`StudioIdentityProvider` by name
(``--Voila.identity_provider_class``); this module imports only jupyter_server and tornado, so the
server process stays free of the library.
"""

from __future__ import annotations

import inspect

from jupyter_server.auth.identity import PasswordIdentityProvider, User
from tornado.web import HTTPError, RequestHandler
from tornado.websocket import WebSocketHandler

#: What a request without the token is told (the 403 page's line).
TOKEN_REQUIRED = (
    "this studio needs its token: open the address that make studio printed (http://127.0.0.1:PORT/?token=...)"
)


class StudioIdentityProvider(PasswordIdentityProvider):
    """jupyter_server's token identity (``?token=...`` once, then its login cookie), without a login page.

    * A request with neither the token nor the login cookie of this run gets 403 and
      :data:`TOKEN_REQUIRED`, not jupyter_server's login form (whose hints name ``jupyter server list``
      and which offers to store a password in the user's Jupyter configuration).
    * An authenticated page request also gets tornado's ``_xsrf`` cookie: when the studio's tab closes,
      Voila's page posts ``voila/api/shutdown/<kernel id>`` with the value of that cookie; Voila's page
      handler does not set it, and without it the post is refused (403) and the kernel lives on. The
      post is checked as tornado checks any form (cookie and field agree): other sites cannot send it.
    """

    async def get_user(self, handler: RequestHandler) -> User | None:  # type: ignore[override]
        """The request's user; raises 403 (:data:`TOKEN_REQUIRED`) when it has no valid token or login cookie.

        Raises
        ------
        tornado.web.HTTPError
            403 for a request without this run's token or its login cookie.
        """
        user = super().get_user(handler)
        if inspect.isawaitable(user):
            user = await user
        # the handler's prepare() sets current_user next; its error page and tornado's xsrf_token read it
        handler.current_user = user
        if user is None:
            raise HTTPError(403, TOKEN_REQUIRED, reason=TOKEN_REQUIRED)  # the reason is the error page's heading
        if handler.request.method == "GET" and not isinstance(handler, WebSocketHandler):
            _ = handler.xsrf_token  # tornado sets the _xsrf cookie the first time the token is read
        return user
