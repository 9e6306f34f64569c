"""Console filtering, buffer and CSV without a roscore."""
import pytest

from rqt_console.console_core import (DEBUG, ERROR, INFO, WARN, ConsoleModel, Filter, Message,
                                      from_csv, to_csv)


def msgs():
    return [Message('starting up', INFO, '/talker', (100, 5), ['/rosout', '/chatter'], 'a.py:main:1'),
            Message('low battery', WARN, '/base', (101, 0), ['/rosout'], 'b.cpp:run:20'),
            Message('motor fault 3', ERROR, '/base', (102, 0), ['/rosout'], 'b.cpp:run:30'),
            Message('tick', DEBUG, '/talker', (103, 0), ['/rosout'], 'a.py:loop:9')]


def test_newest_first_and_limit():
    m = ConsoleModel(limit=3)
    m.add(msgs())
    assert [x.message for x in m.messages] == ['tick', 'motor fault 3', 'low battery']
    assert [x.id for x in m.messages] == [4, 3, 2]


def test_exclude_by_severity_and_node():
    m = ConsoleModel()
    m.add(msgs())
    m.exclude = [Filter('severity', severities=[DEBUG, INFO])]
    assert [x.message for x in m.visible()] == ['motor fault 3', 'low battery']
    m.exclude.append(Filter('node', nodes=['/base']))
    assert m.visible() == []
    assert m.status_text(0) == 'Displaying 0 of 4 messages'


def test_empty_filters_exclude_nothing():
    m = ConsoleModel()
    m.add(msgs())
    m.exclude = [Filter('severity')]
    m.highlight = [Filter('message')]
    assert len(m.visible()) == 4 and m.status_text(4) == 'Displaying 4 messages'
    assert all(m.is_highlighted(x) for x in m.messages)


def test_highlight_text_regex_and_show_only():
    m = ConsoleModel()
    m.add(msgs())
    m.highlight = [Filter('message', text=r'fault \d', regex=True)]
    m.show_highlighted_only = True
    assert [x.message for x in m.visible()] == ['motor fault 3']
    m.highlight = [Filter('message', text='fault \\d')]          # plain text: no match
    assert m.visible() == []


def test_topic_location_custom_time():
    m = ConsoleModel()
    m.add(msgs())
    assert [x.message for x in m.messages if Filter('topic', topics=['/chatter']).matches(x)] == ['starting up']
    assert len([x for x in m.messages if Filter('location', text='b.cpp').matches(x)]) == 2
    custom = Filter('custom', severities=[ERROR], nodes=['/base'], text='motor')
    assert [x.message for x in m.messages if custom.matches(x)] == ['motor fault 3']
    t = Filter('time', start=101.5, end=102.5)
    assert [x.message for x in m.messages if t.matches(x)] == ['motor fault 3']


def test_csv_round_trip_and_format():
    text = to_csv(msgs()[:1])
    assert text.splitlines()[0] == '"message";"severity";"node";"stamp";"topics";"location"'
    assert text.splitlines()[1] == '"starting up";"2";"/talker";"100.000000005";"/rosout,/chatter";"a.py:main:1"'
    back = from_csv(to_csv(msgs()))
    assert [(x.message, x.severity, x.node, x.stamp, x.topics) for x in back] == \
        [(x.message, x.severity, x.node, x.stamp, x.topics) for x in msgs()]
    with pytest.raises(ValueError, match='header'):
        from_csv('a;b\n')


def test_stamp_text_has_nanoseconds_and_date():
    text = Message(stamp=(0, 42)).stamp_text()
    assert text.endswith(')') and '.000000042 (' in text
