"""Words from below and the small shapes of words: OS errors by errno, library words quoted,
lists joined with a translated "or", a joint value that depends on t told apart by its class."""

from __future__ import annotations

import errno
import os

import pytest

from bras_kit.core.errors import ParameterError, TimeInJointValueError, os_reason
from bras_kit.core.i18n import say
from bras_kit.core.wording import either, joined, quoted


@pytest.mark.parametrize("code", [errno.ENOENT, errno.EACCES, errno.EISDIR, errno.ENOTDIR, errno.EEXIST,
                                  errno.ENOSPC, errno.EROFS, errno.ELOOP, errno.ENAMETOOLONG])
def test_a_known_os_error_is_the_c_library_text_in_english_and_translated_in_french(code):
    reason = os_reason(OSError(code, os.strerror(code)))
    assert say(reason, "en") == os.strerror(code)
    french = say(reason, "fr")
    assert french and french != os.strerror(code) and "«" not in french


def test_an_unknown_os_error_is_quoted_after_a_french_sentence():
    reason = os_reason(OSError(errno.EFAULT, "Bad address"))
    assert say(reason, "en") == "Bad address"
    assert say(reason, "fr") == "le système répond : « Bad address »"


def test_an_os_error_with_its_own_words_is_not_taken_for_the_usual_one():
    reason = os_reason(OSError(errno.ENOENT, "no such thing here"))
    assert say(reason, "fr").endswith("« no such thing here »")


def test_library_words_are_kept_as_written_and_quoted_in_french():
    assert say(quoted("expected ',' or ']'"), "en") == "expected ',' or ']'"
    assert say(quoted("expected ',' or ']'"), "fr") == "« expected ',' or ']' »"


def test_lists_are_joined_with_the_word_of_the_language():
    assert say(either(["bras_length", "bras_width", "bras_mass"]), "en") == "bras_length or bras_width or bras_mass"
    assert say(either(["bras_length", "bras_width"]), "fr") == "bras_length ou bras_width"
    assert say(joined(["a", "b", "c"], "; "), "en") == "a; b; c"
    assert joined([]) == "" and either([]) == ""


def test_a_joint_value_depending_on_t_is_its_own_error_class():
    from bras_kit.model.expr import parse_joint_value

    with pytest.raises(TimeInJointValueError):
        parse_joint_value("0.5*t")
    with pytest.raises(ParameterError) as caught:
        parse_joint_value("abc")
    assert not isinstance(caught.value, TimeInJointValueError)


def test_the_command_line_says_which_it_was_without_reading_the_text(run_cli):
    code, _, err = run_cli("--lang", "fr", "fk", "--set", "coude=sin(t)")
    assert code == 2 and "dépend du temps t" in err and "n'est pas un nombre" not in err
    code, _, err = run_cli("--lang", "fr", "fk", "--set", "coude=abc")
    assert code == 2 and "la valeur articulaire n'est pas un nombre" in err
