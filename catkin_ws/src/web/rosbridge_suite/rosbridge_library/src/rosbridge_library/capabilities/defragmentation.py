"""fragment: a long client message split in parts; joined when all arrived, then handled as
if it had come whole. Parts of a message unfinished for fragment_timeout s are dropped."""
import time

from rosbridge_library.capabilities.base import Capability


class Defragment(Capability):
    def __init__(self, protocol, clock=time.monotonic):
        Capability.__init__(self, protocol)
        self.clock = clock
        self.received = {}      # id -> {'total', 'parts': {num: data}, 'last': t}
        protocol.register_operation('fragment', self.fragment)

    def fragment(self, msg):
        mid = msg.get('id')
        if mid is None:
            raise Exception('a fragment needs an id')
        data = self.arg(msg, 'data', str)
        num = self.arg(msg, 'num', int)
        total = self.arg(msg, 'total', int)
        if total < 1 or not 0 <= num < total:
            raise Exception('fragment %d of %d is out of range' % (num, total))
        now = self.clock()
        timeout = self.protocol.settings.get('fragment_timeout') or 600
        for key in [k for k, v in self.received.items() if now - v['last'] > timeout]:
            self.protocol.log('warning', 'fragment: dropped the unfinished message %s after '
                              'fragment_timeout %s s' % (key, timeout), key)
            del self.received[key]
        entry = self.received.setdefault(mid, {'total': total, 'parts': {}, 'last': now})
        if entry['total'] != total:
            del self.received[mid]
            raise Exception('fragments of %s disagree on total (%d, %d)'
                            % (mid, entry['total'], total))
        entry['parts'][num] = data
        entry['last'] = now
        limit = self.protocol.settings.get('max_message_size')
        size = sum(len(p) for p in entry['parts'].values())
        if limit and size > limit:
            del self.received[mid]
            raise Exception('fragmented message %s exceeds max_message_size %d' % (mid, limit))
        if len(entry['parts']) == total:
            del self.received[mid]
            self.protocol.incoming(''.join(entry['parts'][i] for i in range(total)))
