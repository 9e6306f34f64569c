"""rosbridge_server without ROS: the bounded client queue and the parameter parsing."""
import pytest

from rosbridge_server import settings
from rosbridge_server.client_queue import ClientQueue


def test_queue_wakes_the_writer_once_and_keeps_order():
    q = ClientQueue(max_messages=10, max_bytes=1000)
    assert q.put('a') is True          # idle writer: start it
    assert q.put('b') is False         # already draining
    assert q.get() == ('a', False) and q.get() == ('b', False)
    assert q.get() is None             # writer stops...
    assert q.put('c') is True          # ...and is started again


def test_queue_drops_the_oldest_past_its_bounds():
    q = ClientQueue(max_messages=3, max_bytes=10 ** 6)
    for i in range(10):
        q.put(str(i))
    assert len(q) == 3 and q.dropped == 7
    assert [q.get()[0] for _ in range(3)] == ['7', '8', '9']
    q = ClientQueue(max_messages=100, max_bytes=25)
    for i in range(10):
        q.put(b'x' * 10, True)
    assert q.bytes <= 25 and q.dropped == 8 and q.high_water <= 25
    q = ClientQueue(max_messages=100, max_bytes=5)
    q.put('a' * 50)                    # one frame larger than the bound still goes
    assert len(q) == 1


def test_closed_queue_takes_nothing():
    q = ClientQueue()
    q.put('a')
    q.close()
    assert q.put('b') is False and q.get() is None and q.bytes == 0


def test_settings_defaults_as_the_original_launch_gives_them():
    launch = {'port': 9090, 'address': '0.0.0.0', 'max_message_size': 'None',
              'websocket_external_port': 'None', 'topics_glob': '[*]', 'services_glob': '[*]',
              'params_glob': '[*]', 'unregister_timeout': 10, 'retry_startup_delay': 5}
    s = settings.read(lambda n, d: launch.get(n, d))
    assert s['port'] == 9090 and s['address'] == '' and s['max_message_size'] is None
    assert s['topics_glob'] == ['*'] and s['unregister_timeout'] == 10.0
    assert s['fragment_timeout'] == 600 and s['delay_between_messages'] == 0
    assert settings.protocol_settings(s)['max_message_size'] == 10 * 1024 * 1024


def test_glob_lists():
    assert settings.parse_glob("['/turtle1/*', '/rosout']", 'topics_glob') == \
        ['/turtle1/*', '/rosout']
    assert settings.parse_glob('[]', 'x') == [] and settings.parse_glob('', 'x') == []


@pytest.mark.parametrize('name,value,needle', [
    ('port', 'abc', '~port: expected an integer'),
    ('port', 70000, '~port: expected 0..65535'),
    ('fragment_timeout', -1, '~fragment_timeout: must not be negative'),
    ('max_message_size', 0, '~max_message_size: must be positive'),
    ('topics_glob', 5, '~topics_glob: expected a list of globs'),
])
def test_bad_parameters_name_themselves(name, value, needle):
    with pytest.raises(settings.SettingsError) as e:
        settings.read(lambda n, d: value if n == name else d)
    assert needle in str(e.value)


def test_budget_refuses_past_rate_and_refills():
    from rosbridge_server.limits import Budget
    now = [0.0]
    b = Budget(rate=10, capacity=20, clock=lambda: now[0])
    assert all(b.take() for _ in range(20))
    assert not b.take()                  # 21 at once: over
    now[0] += 1.0                        # 10 more a second
    b2 = Budget(rate=10, capacity=20, clock=lambda: now[0])
    assert b2.take(15) and b2.take(5) and not b2.take(1)
    now[0] += 0.5
    assert b2.take(4)
    with pytest.raises(ValueError):
        Budget(0, 1)


def test_counters_report_every_change():
    from rosbridge_server.limits import Counters
    seen = []
    c = Counters(seen.append)
    c.add('clients_cut_off')
    c.add('queue_dropped', 5)
    c.add('queue_dropped', 0)            # nothing happened: no report
    assert c.snapshot()['queue_dropped'] == 5 and c.snapshot()['clients_cut_off'] == 1
    assert len(seen) == 2 and seen[-1]['queue_dropped'] == 5


def test_limit_settings_are_checked():
    s = settings.read({}.get)
    assert s['max_connections_per_address'] == 32 and s['authenticate'] is False
    assert settings.protocol_settings(s)['max_subscriptions'] == 100
    assert settings.read({'authenticate': 'true'}.get)['authenticate'] is True
    with pytest.raises(settings.SettingsError, match='~max_client_subscriptions: must be'):
        settings.read({'max_client_subscriptions': 0}.get)
    with pytest.raises(settings.SettingsError, match='~authenticate: expected true or false'):
        settings.read({'authenticate': 'maybe'}.get)


def test_address_budgets_penalty_and_rest():
    from rosbridge_server.limits import AddressBudgets
    now = [0.0]
    b = AddressBudgets(100, 10, 1, clock=lambda: now[0])
    assert b.bytes.take(150) and b.messages.take(1) and b.rested() is False
    now[0] += 10.0
    assert b.rested()
    b.penalize()                          # cut off: nothing passes for capacity / rate s
    assert not b.bytes.take(1) and not b.messages.take(1)
    now[0] += 1.9
    assert not b.bytes.take(1)            # 2 s to climb from -capacity (-200 bytes) to 0
    now[0] += 0.5
    assert b.bytes.take(1) and b.messages.take(1)
    assert b.should_log() and not b.should_log() and b.unlogged == 1
    now[0] += 6.0
    assert b.should_log()
