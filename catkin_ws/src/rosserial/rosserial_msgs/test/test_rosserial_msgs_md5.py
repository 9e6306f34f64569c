"""rosserial_msgs: every message and service has the md5 sum of the original (rosserial 0.9.2);
a device built with the original ros_lib checks these sums during negotiation."""
import pytest

from course_testing.msgs import generated_types, md5_of

NOETIC_MD5 = {
    ('msg', 'TopicInfo'): '0ad51f88fc44892f8c10684077646005',
    ('msg', 'Log'): '11abd731c25933261cd6183bd12d6295',
    ('srv', 'RequestParam'): 'd7a0c2be00c9fd03cc69f2863de9c4d9',
    ('srv', 'RequestMessageInfo'): '6416d80296dfbbdd5f7b2cee839f9316',
    ('srv', 'RequestServiceInfo'): '0961604b984b94b0b68e8074882be071',
}


@pytest.mark.parametrize('kind,name', sorted(NOETIC_MD5))
def test_generated_class_md5(kind, name):
    assert md5_of('rosserial_msgs', kind, name) == NOETIC_MD5[(kind, name)]


def test_every_definition_is_checked():
    assert generated_types('rosserial_msgs') == set(NOETIC_MD5)


def test_request_param_halves():
    from rosserial_msgs.srv import RequestParamRequest, RequestParamResponse
    assert RequestParamResponse._md5sum == '9f0e98bda65981986ddf53afa7a40e49'
    assert RequestParamRequest._md5sum.startswith('c1f3d28f')
    assert RequestParamRequest._md5sum.endswith('c667')


def test_topic_info_constants_and_fields():
    from rosserial_msgs.msg import TopicInfo, Log
    assert (TopicInfo.ID_PUBLISHER, TopicInfo.ID_SUBSCRIBER, TopicInfo.ID_SERVICE_SERVER,
            TopicInfo.ID_SERVICE_CLIENT, TopicInfo.ID_PARAMETER_REQUEST, TopicInfo.ID_LOG,
            TopicInfo.ID_TIME, TopicInfo.ID_TX_STOP) == (0, 1, 2, 4, 6, 7, 10, 11)
    assert TopicInfo.__slots__ == ['topic_id', 'topic_name', 'message_type', 'md5sum',
                                   'buffer_size']
    assert (Log.ROSDEBUG, Log.INFO, Log.WARN, Log.ERROR, Log.FATAL) == (0, 1, 2, 3, 4)
