// lcm-java (lcm-spy's decoder) reads a message followed by a signature
// trailer (common/bus_signing.h): the message's fields, the trailer
// ignored. Run by lcmtypes_test as a single-file program:
//   java -cp lcm.jar:simpartner_lcmtypes.jar SignedDecode.java
public class SignedDecode {
  public static void main(String[] args) throws Exception {
    simpartner.control_t c = new simpartner.control_t();
    c.sender = "x@y:1";
    c.action = 3;
    c.steps = 7;
    java.io.ByteArrayOutputStream bytes = new java.io.ByteArrayOutputStream();
    c.encode(new java.io.DataOutputStream(bytes));
    byte[] message = bytes.toByteArray();
    byte[] signed = java.util.Arrays.copyOf(message, message.length + 36);
    byte[] magic = {'S', 'P', 'S', '1'};
    System.arraycopy(magic, 0, signed, signed.length - 4, 4);
    simpartner.control_t d = new simpartner.control_t(signed);
    System.out.println("sender=" + d.sender + " action=" + d.action + " steps=" + d.steps);
  }
}
