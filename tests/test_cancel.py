"""The cancel token: cancelled once, with the first reason given."""

from __future__ import annotations

from homebot.cancel import CancelToken


def test_a_token_is_not_cancelled_until_someone_cancels_it() -> None:
    token = CancelToken()
    assert not token.cancelled and token.reason == ""
    token.cancel("emergency stop")
    token.cancel("the console is closing")
    assert token.cancelled and token.reason == "emergency stop"
    assert "emergency stop" in repr(token)


def test_a_token_cancelled_without_a_reason_says_cancelled() -> None:
    token = CancelToken()
    token.cancel()
    assert token.reason == "cancelled"
